#!/usr/bin/env python3
"""Helpers of scripts/bench-report.sh (run that, not this).

  bench_report.py callgrind BIN OUT.json     instructions per call of every op (valgrind)
  bench_report.py firmware FWTARGET OUT.json  M4F numbers from scripts/firmware.sh's run
  bench_report.py render DIR > BENCHMARKS.md  DIR holds machine.json, criterion dir path,
                                              pytransform3d.json, flops.json, callgrind.json,
                                              firmware.json, pinocchio.txt, fit_bench.txt,
                                              firmware_targets.md (kept as it is)
  bench_report.py pinocchio-ir FK_BENCH        Pinocchio FK instructions per call (valgrind)
  bench_report.py selftest                    the line parsers on made-up lines
"""

import glob
import json
import os
import re
import subprocess
import sys
from statistics import median


# ---------------------------------------------------------------- callgrind
def callgrind_ir(bin_, op, reps):
    out = "/tmp/ppoe-bench-callgrind.%d.out" % os.getpid()
    env = dict(os.environ, PPOE_CALLGRIND=op, PPOE_CALLGRIND_REPS=str(reps))
    subprocess.run(
        [
            "valgrind",
            "--tool=callgrind",
            "--callgrind-out-file=" + out,
            "--collect-atstart=no",
            "--toggle-collect=*callgrind_region*",
            bin_,
        ],
        env=env,
        check=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    with open(out) as f:
        for line in f:
            if line.startswith("totals:") or line.startswith("summary:"):
                ir = int(line.split()[1])
                break
    os.remove(out)
    return ir


def cmd_pinocchio_ir(fk_bench):
    """Instructions per forwardKinematics call of each robot: two whole-program runs of the
    harness (1000 and 21000 calls of one fixed-configuration batch, its "fixed" mode)
    under callgrind, the difference / 20000, so that model building and the check cancel
    out."""
    for robot in ("seed", "arm7"):
        tot = []
        for calls in (1000, 21000):
            out = "/tmp/ppoe-bench-pin-callgrind.%d.out" % os.getpid()
            subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out,
                            fk_bench, "1", str(calls), robot, "fixed"],
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            with open(out) as f:
                tot.append(next(int(l.split()[1]) for l in f
                                if l.startswith("summary:") or l.startswith("totals:")))
            os.remove(out)
        print("pinocchio_ir robot=%s ir_per_call=%.0f" % (robot, (tot[1] - tot[0]) / 20000))


def cmd_callgrind(bin_, out):
    ops = subprocess.run(
        [bin_], env=dict(os.environ, PPOE_CALLGRIND="list"), capture_output=True, text=True,
        check=True,
    ).stdout.split()
    reps = 200
    res = {}
    empty = {}
    for op in ops:
        ir = callgrind_ir(bin_, op, reps) / reps
        if op.startswith("empty/"):
            empty[op.split("/")[1]] = ir
        res[op] = ir
        print("callgrind: %-34s %10.1f Ir/call (raw)" % (op, ir), file=sys.stderr)
    net = {}
    for op, ir in res.items():
        t = "f32" if "/f32" in op else "f64"
        if not op.startswith("empty/"):
            net[op] = ir - empty.get(t, 0.0)
    json.dump({"reps": reps, "overhead": empty, "ir_per_call": net}, open(out, "w"), indent=1)


# ---------------------------------------------------------------- key=value lines
def kv_lines(text, prefix):
    """The lines `<prefix> k=v k=v ...` of text as dicts (other lines are ignored)."""
    rows = []
    for line in (text or "").splitlines():
        parts = line.split()
        if not parts or parts[0] != prefix:
            continue
        rows.append(dict(p.split("=", 1) for p in parts[1:] if "=" in p))
    return rows


def read_text(path):
    try:
        return open(path).read()
    except OSError:
        return None


def step_error(text):
    """The reason a step left instead of results (`error: ...`), or None."""
    if text is None:
        return "the step did not run"
    if text.startswith("error: "):
        return text[len("error: "):].strip()
    return None


def selftest():
    fit = ("fit_bench robot=seed.urdf joints=6 model=joint tracker=no samples=2000 median_s=0.0123"
           " iters=7 converged=true\nnoise line\n")
    rows = kv_lines(fit, "fit_bench")
    assert rows == [{"robot": "seed.urdf", "joints": "6", "model": "joint", "tracker": "no",
                     "samples": "2000", "median_s": "0.0123", "iters": "7",
                     "converged": "true"}], rows
    assert "fit_bench" in render_fit(fit), render_fit(fit)
    cal = fit + ("fit_calibration_bench robot=arm7.urdf joints=7 model=joint estimate=base,tip"
                 " samples=2000 median_s=2.5 rounds=4 fits=true\n")
    assert "| arm7.urdf | 7 | joint | base,tip | 2000 | 2.5 | 4 | true |" in render_fit(cal)
    pin = ("versions pin=4.1.0 gxx=12.2.0\npinocchio robot=seed joints=6 ns_per_call=153.07"
           " min_ns=151.81 batches=7 calls=5000 max_abs_err=2.220e-16\n")
    r = kv_lines(pin, "pinocchio")
    assert r[0]["robot"] == "seed" and float(r[0]["ns_per_call"]) == 153.07, r
    assert pinocchio_batch_ns(pin) == {"seed": 153.07}
    varied = pin + "pinocchio_batch robot=seed joints=6 ns_per_config=160.50 configs=256 batches=7\n"
    assert pinocchio_batch_ns(varied) == {"seed": 160.5} and pinocchio_ns(varied) == {"seed": 153.07}
    assert kv_lines(pin, "versions")[0]["pin"] == "4.1.0"
    assert step_error("error: skipped: g++ is not installed") == "skipped: g++ is not installed"
    assert step_error(pin) is None
    lr = ("case lanes | f64 ns | f32 ns | median of per-round f32/f64\n"
          "seed       0 |   376.0 |   374.1 | 0.996\n"
          "f64: chain7 - chain6 = 50.1 ns, chain8 - chain7 = 49.0 ns, chain6 / 6 = 60.0 ns\n")
    assert lanes_ratio_rows(lr) == {"seed": (376.0, 374.1, 0.996)}, lanes_ratio_rows(lr)
    assert "| seed | 376.0 | 374.1 | 0.996 |" in render_lanes_ratio(lr)
    assert "Not measured" in render_lanes_ratio("error: cargo bench --bench lanes_ratio failed")[2]
    pr = lr + ("ports case | ppoe f64 ns | 4x4 port ns | closed port ns | median 4x4/ppoe | median closed/ppoe\n"
               "ports seed_dense |   317.0 |  1220.4 |   878.0 | 3.870 | 2.728\n")
    assert port_rows(pr) == {"seed_dense": (317.0, 1220.4, 878.0, 3.87, 2.728)}, port_rows(pr)
    assert lanes_ratio_rows(pr) == lanes_ratio_rows(lr)
    assert "| seed_dense | 317.0 | 1220.4 | 878.0 | 3.87× | 2.73× |" in render_ports(pr)
    pt = port_target_rows(pr)
    assert pt[0].endswith("| 3.87× | met |") and pt[1].endswith("| 2.73× | **missed** (91% of it) |"), pt
    assert len(pt) == 8 and pt[2].endswith("| not measured | — |"), pt
    lt = lanes_target_rows(lr.replace("seed  ", "arm7  ") + "seed_dense 0 | 300.0 | 306.0 | 1.020\n")
    assert lt[0].endswith("| 1.020 | **missed** by 2.0% |") and lt[1].endswith("| 0.996 | met |"), lt
    assert len(lt) == 4 and "batch table's configuration" in lt[2] and "0.996" not in lt[2], lt
    alt = ("round 1\n"
           "pinocchio_batch robot=seed joints=6 ns_per_config=200.00 configs=256 batches=21\n"
           "pinocchio_batch robot=arm7 joints=7 ns_per_config=250.00 configs=256 batches=21\n"
           "batch_seed/batch/f64    time:   [47.0 µs 51.2 µs 52.0 µs]\n"
           "batch_7dof/batch/f64    time:   [64.0 µs 64.0 µs 64.0 µs]\n"
           "round 2\n"
           "pinocchio_batch robot=seed joints=6 ns_per_config=100.00 configs=256 batches=21\n"
           "batch_seed/batch/f64    time:   [0.0512 ms 0.0512 ms 0.0512 ms]\n"
           "round 3\n"
           "batch_seed/batch/f64    time:   [51.2 µs 51.2 µs 51.2 µs]\n")
    ar = alternating_ratios(alt)
    assert [round(r[2], 3) for r in ar["seed"]] == [1.0, 2.0] and ar["arm7"] == [(250.0, 250.0, 1.0)], ar
    assert "| seed | 2 | 200.0 | 150.0 | 1.50× | 1.00–2.00× |" in render_alternating(alt), render_alternating(alt)
    at = alternating_target_rows(alt)
    assert at[0].endswith("| 1.50 | **missed** by 50% |") and at[1].endswith("| 1.00 | met |"), at
    assert "Not measured" in render_alternating("error: not measured (no Pinocchio harness in this run)")[2]
    cgu = ("round 1\nbuild default\n"
           "batch_seed/batch/f64    time:   [47.0 µs 51.2 µs 52.0 µs]\n"
           "batch_seed/single/f32   time:   [300.0 ns 300.0 ns 300.0 ns]\n"
           "build one_unit\n"
           "batch_seed/batch/f64    time:   [0.0768 ms 0.0768 ms 0.0768 ms]\n"
           "round 2\nbuild default\n"
           "batch_seed/batch/f64    time:   [51.2 µs 51.2 µs 51.2 µs]\n"
           "build one_unit\n"
           "batch_seed/batch/f64    time:   [51.2 µs 51.2 µs 51.2 µs]\n"
           "batch_seed/single/f32   time:   [1.0 µs 1.0 µs 1.0 µs]\n")
    cr = codegen_unit_rounds(cgu)
    assert cr == {("seed", "batch", "f64"): [(200.0, 300.0), (200.0, 200.0)]}, cr
    assert "| seed | batch | f64 | 2 | 200.0 | 250.0 | 1.25× |" in render_codegen_units(cgu), render_codegen_units(cgu)
    assert "Not measured" in render_codegen_units("error: the one-codegen-unit build failed")[2]
    print("bench_report selftest: 14 passed, 0 failed")


# ---------------------------------------------------------------- firmware
def sh(*a):
    return subprocess.run(list(a), capture_output=True, text=True, check=True).stdout


def fw_function_sizes(elf):
    """name -> (addr, size) for text symbols (demangled)."""
    syms = {}
    for line in sh("arm-none-eabi-nm", "-C", "--size-sort", "-S", elf).splitlines():
        parts = line.split(None, 3)
        if len(parts) == 4 and parts[2] in "tTwW":
            syms[parts[3]] = (int(parts[0], 16) & ~1, int(parts[1], 16))
    return syms


def fw_callgraph(elf):
    """function (mangled label) -> set of callees, from objdump's bl/b.w targets."""
    graph, cur = {}, None
    for line in sh("arm-none-eabi-objdump", "-d", "--no-show-raw-insn", elf).splitlines():
        m = re.match(r"^[0-9a-f]+ <([^>]+)>:$", line)
        if m:
            cur = m.group(1)
            graph[cur] = set()
            continue
        m = re.search(r"\s(bl|b\.w|b)\s+[0-9a-f]+ <([^>+]+)>", line)
        if cur and m and m.group(2) != cur:
            graph[cur].add(m.group(2))
    return graph


def fw_call_sites(elf):
    """function -> {callee: number of bl call sites}."""
    out, cur = {}, None
    for line in sh("arm-none-eabi-objdump", "-d", "--no-show-raw-insn", elf).splitlines():
        m = re.match(r"^[0-9a-f]+ <([^>]+)>:$", line)
        if m:
            cur = m.group(1)
            out[cur] = {}
            continue
        m = re.search(r"\sbl\s+[0-9a-f]+ <([^>+]+)>", line)
        if cur and m:
            out[cur][m.group(1)] = out[cur].get(m.group(1), 0) + 1
    return out


def closure(graph, root):
    seen, todo = set(), [root]
    while todo:
        f = todo.pop()
        if f in seen:
            continue
        seen.add(f)
        todo.extend(graph.get(f, ()))
    return seen


def cmd_firmware(td, out):
    res = {}
    log = os.path.join(td, "firmware-logs", "thumbv7em-none-eabihf-icount.txt")
    if os.path.exists(log):
        txt = open(log).read()
        m = re.search(r"^systick ticks per PPOE call: f32 (\d+) f64 (\d+)", txt, re.M)
        if m:
            res["ppoe_insns"] = {"f32": int(m.group(1)) * 40, "f64": int(m.group(2)) * 40}
        for m in re.finditer(
            r"^systick ticks per 64 calls of (\w+): f32 (\d+) f64 (\d+)", txt, re.M
        ):
            res.setdefault("op_insns", {})[m.group(1)] = {
                "f32": int(m.group(2)) * 40 / 64,
                "f64": int(m.group(3)) * 40 / 64,
            }
        m = re.search(r"^stack per PPOE call[^:]*: f32 (\d+) B, f64 (\d+) B", txt, re.M)
        if m:
            res["stack"] = {"f32": int(m.group(1)), "f64": int(m.group(2))}
    elf = os.path.join(td, "thumbv7em-none-eabihf", "release", "ppoe-firmware")
    if os.path.exists(elf):
        syms = fw_function_sizes(elf)
        mangled = fw_function_sizes_mangled(elf)
        graph = fw_callgraph(elf)
        own = {n: s for n, (_, s) in syms.items() if n.startswith("ppoe::") or "<ppoe::" in n}
        res["own_functions"] = own
        res["own_bytes"] = sum(own.values())
        for t in ("f32", "f64"):
            root = "ppoe_seed_" + t
            path = closure(graph, root)
            rows = {f: mangled.get(f, 0) for f in path}
            res.setdefault("path", {})[t] = {
                "bytes": sum(rows.values()),
                "ppoe_bytes": sum(v for f, v in rows.items() if "ppoe" in f),
                "functions": len(rows),
                "soft_f64_calls": sorted(f for f in path if re.match(r"__aeabi_d|__adddf|__muldf", f)),
                "mem_calls": sorted(f for f in path if "__aeabi_mem" in f or f in ("memcpy", "memset")),
                "largest": sorted(
                    ((sh("arm-none-eabi-c++filt", f).strip() if f.startswith("_R") else f, s)
                     for f, s in rows.items()),
                    key=lambda x: -x[1],
                )[:8],
            }
        # Direct calls of the f32 kernels (counted call sites).
        dc = {}
        for label, callees in fw_call_sites(elf).items():
            for key, nice in (("TransformfE20transport_covariance", "transport_covariance<f32>"),
                              ("3se33expfE", "se3::exp<f32>"), ("ppoe_seed_f32", "ppoe_seed_f32")):
                if key in label:
                    dc[nice] = {re.sub(r"\[[0-9a-f]{16}\]", "", sh("arm-none-eabi-c++filt", k).strip()): v
                                for k, v in callees.items()}
        res["direct_calls"] = dc
        both = closure(graph, "ppoe_seed_f32") | closure(graph, "ppoe_seed_f64")
        res["path_both_bytes"] = sum(mangled.get(f, 0) for f in both)
        size = sh("arm-none-eabi-size", elf).splitlines()[1].split()
        res["elf_size"] = {"text": int(size[0]), "data": int(size[1]), "bss": int(size[2])}
        allsyms = sh("arm-none-eabi-nm", elf)
        alloc = [l.split()[-1] for l in allsyms.splitlines()
                 if re.search(r"__rust_alloc|__rg_alloc|__rust_no_alloc|alloc5alloc|__rdl_alloc|malloc", l)]
        res["alloc_symbols"] = alloc
    json.dump(res, open(out, "w"), indent=1)


def fw_function_sizes_mangled(elf):
    syms = {}
    for line in sh("arm-none-eabi-nm", "--size-sort", "-S", elf).splitlines():
        parts = line.split(None, 3)
        if len(parts) == 4 and parts[2] in "tTwW":
            syms[parts[3]] = int(parts[1], 16)
    return syms


# ---------------------------------------------------------------- robots, rank-1, fit
def ns(v):
    return "—" if v is None else ("%.1f" % v if v < 1000 else "%.0f" % v)


def pinocchio_ns(pin_text):
    """robot name -> Pinocchio FK median ns per call (from fk_bench's lines)."""
    return {r["robot"]: float(r["ns_per_call"]) for r in kv_lines(pin_text, "pinocchio")}


def pinocchio_batch_ns(pin_text):
    """robot name -> Pinocchio FK median ns per call cycling through 256 varied
    configurations (fk_bench's pinocchio_batch lines), else its fixed-configuration time."""
    varied = {r["robot"]: float(r["ns_per_config"]) for r in kv_lines(pin_text, "pinocchio_batch")}
    return {**pinocchio_ns(pin_text), **varied}


def render_robots(crit, pin_text, ir):
    """Seed and 7-joint arm: ppoe PPOE/FK, the nalgebra port, Pinocchio's FK (ns per call),
    and their instruction counts where callgrind ran."""
    pin = pinocchio_ns(pin_text)
    pin_ir = {r["robot"]: float(r["ir_per_call"]) for r in kv_lines(pin_text, "pinocchio_ir")}
    err = step_error(pin_text)
    ver = (kv_lines(pin_text, "versions") or [{}])[0]
    L = ["## Seed robot (6 joints) and 7-joint arm: ppoe, the nalgebra ports and Pinocchio", ""]
    L.append("Nanoseconds per call (criterion medians; Pinocchio: median of the harness's batches).")
    L.append("The 7-joint arm is test_data/urdf/arm7.urdf (full-rank, correlated joint covariances,")
    L.append("benches/pinocchio/robots.rs); PPOE = `ChainView::ppoe`, second order, right perturbation.")
    L.append("The nalgebra ports invert transforms as general 4×4 matrices (*4×4 inv*, as pytransform3d")
    L.append("does) or by the closed form `(Rᵀ, −Rᵀp)` (*closed*, the faster baseline).")
    L.append("")
    L.append("| robot | ppoe PPOE f64 | ppoe PPOE f32 | ppoe FK f64 | ppoe FK f32 | nalgebra port f64, 4×4 inv | nalgebra port f64, closed | Pinocchio FK f64 | 4×4 inv port / ppoe PPOE (f64) | closed port / ppoe PPOE (f64) | ppoe PPOE / Pinocchio FK | ppoe FK / Pinocchio FK |")
    L.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for robot, key, pkey in (("seed", "seed", "seed"), ("7-joint arm", "7dof", "arm7")):
        g = lambda k: crit.get(k)
        p64, p32 = g("ppoe_%s/ours/f64" % key), g("ppoe_%s/ours/f32" % key)
        f64_, f32_ = g("fk_%s/ours/f64" % key), g("fk_%s/ours/f32" % key)
        n64, pf = g("ppoe_%s/nalgebra/f64" % key), pin.get(pkey)
        c64 = g("ppoe_%s/nalgebra_closed/f64" % key)
        L.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            robot, ns(p64), ns(p32), ns(f64_), ns(f32_), ns(n64), ns(c64), ns(pf), ratio(n64, p64),
            ratio(c64, p64), ratio(p64, pf), ratio(f64_, pf)))
    L.append("")
    if pin:
        L.append("Pinocchio %s (pip package `pin`), `pinocchio::forwardKinematics(model, data, q)` in C++"
                 " (benches/pinocchio/fk_bench.cpp, g++ %s `-O3`, default target like our build,"
                 " header-only so the call is compiled with these flags). The model is built joint by"
                 " joint (RX/RY/RZ where the axis is a coordinate axis, a frame with a negative one turned"
                 " by π, RevoluteUnaligned otherwise)"
                 " from the chain ppoe-build extracts, because urdfdom rejects the seed URDF; before"
                 " timing, its tip pose `oMi[n]·tip` is checked against ppoe's forward kinematics on 3"
                 " configurations per robot (largest element difference: %s). Same configuration as"
                 " the criterion benches, %s batches of %s calls." % (
                     ver.get("pin", "?"), ver.get("gxx", "?"),
                     ", ".join("%s %s" % (r["robot"], r["max_abs_err"]) for r in kv_lines(pin_text, "pinocchio")),
                     kv_lines(pin_text, "pinocchio")[0]["batches"], kv_lines(pin_text, "pinocchio")[0]["calls"]))
    else:
        L.append("Pinocchio: not measured (%s)." % (err or "no result lines"))
    L.append("")
    if ir:
        L.append("Instructions per call, f64 (callgrind; Pinocchio: whole runs of the harness with 1000 and")
        L.append("21000 calls, the difference / 20000):")
        L.append("")
        L.append("| robot | ppoe PPOE | ppoe FK | nalgebra port, 4×4 inv | nalgebra port, closed | Pinocchio FK | ppoe PPOE / Pinocchio FK |")
        L.append("|---|---:|---:|---:|---:|---:|---:|")
        for robot, key, pkey in (("seed", "seed", "seed"), ("7-joint arm", "7dof", "arm7")):
            a = ir.get("ppoe_%s/ours/f64" % key)
            n0 = lambda v: "—" if v is None else "%.0f" % v
            L.append("| %s | %s | %s | %s | %s | %s | %s |" % (
                robot, n0(a), n0(ir.get("fk_%s/ours/f64" % key)),
                n0(ir.get("ppoe_%s/nalgebra/f64" % key)), n0(ir.get("ppoe_%s/nalgebra_closed/f64" % key)),
                n0(pin_ir.get(pkey)), ratio(a, pin_ir.get(pkey))))
        L.append("")
    return L


# Configurations per call of the batch benchmarks (benches/ops.rs, BATCH).
BATCH = 256


def batch_ns(crit, key, impl, t):
    """ns per configuration of the batch benchmarks: the batch call's time / BATCH."""
    v = crit.get("batch_%s/%s/%s" % (key, impl, t))
    return None if v is None else (v / BATCH if impl == "batch" else v)


def render_batch(crit, pin_text):
    """Batch PPOE per configuration against single calls, the nalgebra ports and Pinocchio's
    FK, dense covariances on every joint (benches/ops.rs, batch_ops)."""
    pin = pinocchio_batch_ns(pin_text)
    L = ["## Batch PPOE: many configurations per call, dense covariances on every joint", ""]
    L.append("`ChainView::ppoe_batch` on %d configurations (uniform in [−1, 1] per joint) per call, its" % BATCH)
    L.append("time divided by %d, against a single `ChainView::ppoe` call, the dense nalgebra ports and" % BATCH)
    L.append("Pinocchio's rigid FK (the harness above, cycling through %d configurations of the same" % BATCH)
    L.append("distribution: its `pinocchio_batch` lines), ns per configuration (criterion medians);")
    L.append("every joint has a full-rank covariance (`robots::arm7_covs`), right perturbation, default target.")
    L.append("The two nalgebra ports (benches/baseline_nalgebra.rs) differ only in how they invert a")
    L.append("transform: *4×4 inv* as pytransform3d does (a general matrix inverse), *closed form*")
    L.append("with `(Rᵀ, −Rᵀp)`, which a port may as well use and which is the faster baseline.")
    L.append("")
    L.append("| robot | scalar | batch PPOE / config | single PPOE | nalgebra port, 4×4 inv | nalgebra port, closed form | Pinocchio FK f64 | batch / Pinocchio FK | single / batch | 4×4 inv port / single | closed-form port / single |")
    L.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for robot, key, pkey in (("seed", "seed", "seed"), ("7-joint arm", "7dof", "arm7")):
        for t in ("f64", "f32"):
            b, s1, na, nc = (batch_ns(crit, key, i, t) for i in ("batch", "single", "nalgebra", "nalgebra_closed"))
            pf = pin.get(pkey)
            L.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                robot, t, ns(b), ns(s1), ns(na), ns(nc), ns(pf), ratio(b, pf), ratio(s1, b),
                ratio(na, s1), ratio(nc, s1)))
    L.append("")
    return L


CRITERION_TIME = re.compile(r"^(\S+)\s+time:\s+\[\S+ \S+ ([0-9.]+) (ns|µs|us|ms) ")
UNIT_NS = {"ns": 1.0, "µs": 1e3, "us": 1e3, "ms": 1e6}


def alternating_ratios(text):
    """{robot: [(batch ns per configuration, Pinocchio ns, ratio)] per round} from step 2a's
    rounds: each round's `pinocchio_batch` lines and criterion's `batch_<key>/batch/f64`
    time (its middle estimate, one call on BATCH configurations); a round missing either
    side of a robot gives nothing for it."""
    rounds, cur = [], None
    for line in (text or "").splitlines():
        if line.startswith("round "):
            cur = {"pin": {}, "batch": {}}
            rounds.append(cur)
        elif cur is not None and line.startswith("pinocchio_batch "):
            kv = kv_lines(line, "pinocchio_batch")[0]
            cur["pin"][kv["robot"]] = float(kv["ns_per_config"])
        elif cur is not None:
            m = CRITERION_TIME.match(line)
            if m and m.group(1).endswith("/batch/f64") and m.group(1).startswith("batch_"):
                key = m.group(1)[len("batch_"):].split("/")[0]
                cur["batch"]["arm7" if key == "7dof" else key] = float(m.group(2)) * UNIT_NS[m.group(3)] / BATCH
    out = {}
    for r in rounds:
        for robot, b in r["batch"].items():
            p = r["pin"].get(robot)
            if p:
                out.setdefault(robot, []).append((b, p, b / p))
    return out


def render_alternating(text):
    """Step 2a: the f64 batch per configuration against Pinocchio's FK, alternating rounds."""
    L = ["### Batch / Pinocchio FK in alternating rounds (f64, dense covariances)", ""]
    rows = alternating_ratios(text)
    if not rows:
        return L + ["Not measured in this run (%s)." % (step_error(text) or "no result"), ""]
    L.append("The criterion medians and the harness in the table above are timed minutes apart; here")
    L.append("they alternate round by round (`scripts/bench-report.sh` step 2a: the harness with 21")
    L.append("batches over the 256 varied configurations, then criterion's `batch_*/batch/f64` for 1 s")
    L.append("each), so that load from other work falls on both alike. ns per configuration are")
    L.append("medians over rounds; the ratio is the median of the rounds' own ratios.")
    L.append("")
    L.append("| robot | rounds | batch PPOE / config | Pinocchio FK | batch / Pinocchio FK (median) | rounds' min–max |")
    L.append("|---|---:|---:|---:|---:|---:|")
    for robot, name in (("seed", "seed"), ("arm7", "7-joint arm")):
        rs = rows.get(robot)
        if not rs:
            continue
        ratios = [r[2] for r in rs]
        L.append("| %s | %d | %.1f | %.1f | %.2f× | %.2f–%.2f× |" % (
            name, len(rs), median([r[0] for r in rs]), median([r[1] for r in rs]),
            median(ratios), min(ratios), max(ratios)))
    L.append("")
    return L


def alternating_target_rows(text):
    """Issue 28's batch ≤ Pinocchio FK target from the alternating rounds (step 2a)."""
    rows = alternating_ratios(text)
    L = []
    for robot, name in (("seed", "seed"), ("arm7", "7-joint arm")):
        label = "host f64 batch PPOE per configuration / Pinocchio FK, dense, %s, alternating rounds" % name
        rs = rows.get(robot)
        L.append(at_most_one_row(label, median([x[2] for x in rs]) if rs else None, 2))
    return L


def at_most_one_row(name, r, digits):
    """A targets-table row for a ratio that must be ≤ 1 (`None`: not measured), the ratio
    with `digits` decimals and the miss in percent with `digits` − 2."""
    if r is None:
        return "| %s | ≤ 1 | not measured | — |" % name
    return "| %s | ≤ 1 | %.*f | %s |" % (
        name, digits, r, "met" if r <= 1 else "**missed** by %.*f%%" % (digits - 2, 100 * (r - 1)))


def at_least_row(name, limit, val):
    """A targets-table row for a ratio that must be ≥ `limit` (`None`: not measured)."""
    return "| %s | ≥ %g× | %s | %s |" % (
        name, limit, "not measured" if val is None else "%.2f×" % val,
        "—" if val is None else "met" if val >= limit else "**missed** (%.0f%% of it)" % (100 * val / limit))


def codegen_unit_rounds(text):
    """{(robot, call, scalar): [(default ns, one-unit ns)] per round} from step 1c: each
    round's `build default` then `build one_unit` criterion lines of `batch_<key>/<call>/<T>`,
    ns per configuration (a batch call's time divided by BATCH); a round missing either
    build's line gives nothing for that benchmark."""
    rounds, cur, build = [], None, None
    for line in (text or "").splitlines():
        if line.startswith("round "):
            cur = {"default": {}, "one_unit": {}}
            rounds.append(cur)
        elif cur is not None and line.startswith("build "):
            build = line.split()[1]
        elif cur is not None and build in cur:
            m = CRITERION_TIME.match(line)
            if m and m.group(1).startswith("batch_"):
                key, call, t = m.group(1)[len("batch_"):].split("/")
                v = float(m.group(2)) * UNIT_NS[m.group(3)] / (BATCH if call == "batch" else 1)
                cur[build][("arm7" if key == "7dof" else key, call, t)] = v
    out = {}
    for r in rounds:
        for k, a in r["default"].items():
            if k in r["one_unit"]:
                out.setdefault(k, []).append((a, r["one_unit"][k]))
    return out


def render_codegen_units(text):
    """Step 1c: the batch benchmarks with the core in one codegen unit against the default."""
    L = ["### The core compiled in one codegen unit (reported, not a target)", ""]
    rows = codegen_unit_rounds(text)
    if not rows:
        return L + ["Not measured in this run (%s)." % (step_error(text) or "no result"), ""]
    L.append("Cargo's release and bench profiles compile a crate in 16 codegen units, which rustc's")
    L.append("crate-local ThinLTO optimises once more; `codegen-units = 1` (a common setting for release")
    L.append("builds) gives one optimisation pipeline. `scripts/bench-report.sh` step 1c builds the ops")
    L.append("benchmark again with `--config 'profile.bench.package.ppoe.codegen-units=1'` and alternates")
    L.append("the two binaries round by round (the `batch_` benchmarks, 0.5 s each). ns per configuration")
    L.append("(batch) or per call (single): medians over rounds; the ratio is the median of the rounds' own.")
    L.append("")
    L.append("| robot | call | scalar | rounds | default | one codegen unit | one unit / default |")
    L.append("|---|---|---|---:|---:|---:|---:|")
    for robot, name in (("seed", "seed"), ("arm7", "7-joint arm")):
        for call in ("batch", "single"):
            for t in ("f64", "f32"):
                rs = rows.get((robot, call, t))
                if not rs:
                    continue
                L.append("| %s | %s | %s | %d | %.1f | %.1f | %.2f× |" % (
                    name, call, t, len(rs), median([a for a, _ in rs]), median([b for _, b in rs]),
                    median([b / a for a, b in rs])))
    L.append("")
    return L


def pipe_rows(text, fields, name):
    """{name: floats} of the `<head> | x | y | …` lines of benches/lanes_ratio.rs with
    `fields` numbers after the head, whose head words `name` maps to a row name (None:
    not such a line)."""
    rows = {}
    for line in (text or "").splitlines():
        parts = [x.strip() for x in line.split("|")]
        key = name(parts[0].split()) if len(parts) == fields + 1 else None
        if key is None:
            continue
        try:
            rows[key] = tuple(float(x) for x in parts[1:])
        except ValueError:
            continue
    return rows


def lanes_ratio_rows(text):
    """The `case lanes | f64 ns | f32 ns | ratio` lines of benches/lanes_ratio.rs, as
    {case: (f64 ns, f32 ns, median per-round f32/f64)} (target lanes, 0, only)."""
    return pipe_rows(text, 3, lambda h: h[0] if len(h) == 2 and h[1] == "0" else None)


def rows_section(title, rows, text, prose, header, row):
    """A report section of the rows parsed from `text`: `title`, the `prose` lines, a table
    of `header` (a line and its alignment line) with `row(name, values)` per row; "not
    measured" with the step's error when `text` gave no rows."""
    L = [title, ""]
    if not rows:
        return L + ["Not measured in this run (%s)." % (step_error(text) or "no result"), ""]
    L.extend(prose + [""] + header)
    L.extend(row(name, v) for name, v in rows.items())
    return L + [""]


def render_lanes_ratio(text):
    """The f32/f64 ratios of f32 and f64 batches interleaved in one process (step 1a)."""
    return rows_section(
        "### f32 against f64, interleaved in one process (benches/lanes_ratio.rs)",
        lanes_ratio_rows(text), text, [
            "`cargo bench --bench lanes_ratio -- 201 2000`: 201 rounds, each timing 2000 single",
            "`ChainView::ppoe` calls in f64 then in f32 for every case, so that load from other work",
            "falls on both alike; ns per call are medians over rounds, the ratio is the median of the",
            "rounds' own f32/f64 ratios (below 1: f32 faster). `seed_dense` and `arm7` have the batch",
            "table's dense covariances with the seed example's joint values and the arm's benchmark",
            "configuration; `seed_batch` and `arm7_batch` the same covariances with the configuration",
            "of the batch table's single-call column; `seed` the seed example's covariances; `chainN`",
            "a synthetic N-joint chain."],
        ["| case | f64 ns | f32 ns | f32 / f64 (median of rounds) |", "|---|---:|---:|---:|"],
        lambda name, v: "| %s | %.1f | %.1f | %.3f |" % ((name,) + v))


def port_rows(text):
    """The `ports <case> | ppoe ns | 4x4 port ns | closed port ns | ratio | ratio` lines of
    benches/lanes_ratio.rs, as {case: (ppoe ns, 4×4 port ns, closed port ns, median 4×4/ppoe,
    median closed/ppoe)}."""
    return pipe_rows(text, 5, lambda h: h[1] if len(h) == 2 and h[0] == "ports" else None)


def render_ports(text):
    """ppoe's single call against the nalgebra ports, interleaved in one process (step 1a)."""
    return rows_section(
        "### Single call against the nalgebra ports, interleaved in one process (benches/lanes_ratio.rs)",
        port_rows(text), text, [
            "The same run as the section above: in each of its rounds, after the f32/f64 batches,",
            "2000 f64 `ChainView::ppoe` calls, then 2000 calls of each nalgebra port, for the dense",
            "cases; ns per call are medians over rounds, the ratios the medians of the rounds' own",
            "port/ppoe ratios (above 1: ppoe faster). The ports invert transforms as 4×4 matrices",
            "(as pytransform3d does) or by the closed form `(Rᵀ, −Rᵀp)`."],
        ["| case | ppoe f64 ns | 4×4 inv port ns | closed-form port ns | 4×4 inv port / ppoe | closed-form port / ppoe |",
         "|---|---:|---:|---:|---:|---:|"],
        lambda name, v: "| %s | %.1f | %.1f | %.1f | %.2f× | %.2f× |" % ((name,) + v))


def port_target_rows(text):
    """Issue 28's single call ≥ 3× the dense nalgebra port, from the interleaved measurement
    (both ports), which drifting load disturbs less than criterion medians timed apart."""
    rows = port_rows(text)
    L = []
    for robot, case in DENSE_CASES:
        for port, i in (("4×4 inv", 3), ("closed-form inverse", 4)):
            v = rows[case][i] if case in rows else None
            L.append(at_least_row("host f64 single PPOE vs the nalgebra port (%s), dense, %s,"
                                  " interleaved in one process" % (port, robot), 3, v))
    return L


def render_batch_v3(crit, d):
    """The batch benchmarks of a -C target-cpu=x86-64-v3 build (step 1b) beside the default
    target's, ns per configuration."""
    path = os.path.join(d, "criterion_v3_dir")
    v3 = criterion_medians(open(path).read().strip()) if os.path.exists(path) else {}
    L = ["### The same with `-C target-cpu=x86-64-v3` (reported, not a target)", ""]
    if not v3:
        return L + ["Not measured in this run (the CPU lacks an x86-64-v3 feature, or step 1b failed).", ""]
    L.append("`RUSTFLAGS=\"-C target-cpu=x86-64-v3\"` (AVX2, FMA; Rust contracts no product and sum into")
    L.append("an FMA, so the results are the default build's bits), the `batch_` benchmarks only, right after")
    L.append("the default run; ns per configuration (criterion medians).")
    L.append("")
    L.append("| robot | scalar | batch, default | batch, v3 | single, default | single, v3 | default / v3 (batch) |")
    L.append("|---|---|---:|---:|---:|---:|---:|")
    for robot, key in (("seed", "seed"), ("7-joint arm", "7dof")):
        for t in ("f64", "f32"):
            b, b3 = batch_ns(crit, key, "batch", t), batch_ns(v3, key, "batch", t)
            s1, s3 = batch_ns(crit, key, "single", t), batch_ns(v3, key, "single", t)
            L.append("| %s | %s | %s | %s | %s | %s | %s |" % (robot, t, ns(b), ns(b3), ns(s1), ns(s3), ratio(b, b3)))
    L.append("")
    return L


def render_python_batch(pb, m):
    """The Python package's batch of 10,000 seed configurations (ppoe-py/benches/batch.py)."""
    L = ["## Python package: a batch of 10,000 seed configurations (ppoe-py/benches/batch.py)", ""]
    if not pb or "error" in pb:
        L += ["Not measured in this run (%s)." % ((pb or {}).get("error", "no result")), ""]
        return L
    L.append("From the same run, with the wheel of `scripts/python-check.sh` (its venv,")
    L.append("`target/python-check/venv`: pytransform3d 3.17.0 and numpy from PyPI); load average %s" %
             " ".join("%.2f" % x for x in pb.get("load_average", [])))
    L.append("when it started. Seed robot, joint values uniform in [−1, 1]⁶, the seed example's joint")
    L.append("covariances, `convention=\"pytransform3d\"`; OPENBLAS_NUM_THREADS=%s (numpy's idle BLAS" % pb.get("openblas_num_threads", "unset"))
    L.append("threads would spin on the cores ppoe's threads use); microseconds per configuration, medians of repeats:")
    L.append("")
    L.append("| implementation | µs / configuration | pytransform3d's example is slower by |")
    L.append("|---|---:|---:|")
    ex = pb["pytransform3d_example_us"]
    threads = "every core (%s)" % pb.get("cpu_count", "?")
    rows = (("**ppoe batch**: one `probabilistic_forward_kinematics` call, thetas (10000, 6), covs (6, 6, 6) shared, GIL released, on %s" % threads, "ppoe_batch_us"),
            ("ppoe batch as above with `threads=1`", "ppoe_batch_one_thread_us"),
            ("ppoe batch as the first, writing into the same `out=` arrays every call", "ppoe_batch_out_us"),
            ("ppoe batch with covs (10000, 6, 6, 6), each checked symmetric PSD", "ppoe_batch_per_config_covs_us"),
            ("Python loop of single ppoe calls", "ppoe_loop_us"))
    for name, k in rows:
        if k in pb:
            L.append("| %s | %.3f | %.0f× |" % (name, pb[k], ex / pb[k]))
    L.append("| pytransform3d 3.17.0 example `probabilistic_forward_kinematics` (timed on 200 of the configurations) | %.1f | — |" % ex)
    L.append("")
    L.extend(render_python_interleaved(pb))
    return L


def render_python_interleaved(pb):
    """The example / ppoe batch ratio timed back to back in rounds, against issue 29's target."""
    both, one = pb.get("interleaved_speedup"), pb.get("interleaved_speedup_one_thread")
    if not both or not one:
        return []
    met = "met" if both["median"] >= 5000 else "**missed**"
    repeats = pb["pytransform3d_example_us"] / pb["ppoe_batch_us"]
    return ["The same ratio measured back to back: %d rounds, each timing the ppoe batch (median of"
            % pb.get("interleaved_rounds", 0),
            "3 calls) right before the example on its 200 configurations, so that load from other work",
            "falls on both alike; unlike the medians above, every ppoe call here follows the example's",
            "Python work rather than another ppoe call. Median of the rounds' ratios (min–max):",
            "",
            "| ppoe batch | pytransform3d's example is slower by | rounds' min–max |",
            "|---|---:|---:|",
            "| every core (%s) | %.0f× | %.0f–%.0f× |" % (pb.get("cpu_count", "?"), both["median"], both["min"], both["max"]),
            "| `threads=1` | %.0f× | %.0f–%.0f× |" % (one["median"], one["min"], one["max"]),
            "",
            "Target (issue 29): batch ≥ 5,000× pytransform3d's example: %s by the back-to-back median"
            % met,
            "(%.0f×), %s by the medians of repeats above (%.0f×)." % (
                both["median"], "met" if repeats >= 5000 else "missed", repeats),
            ""]


def render_rank1(crit):
    L = ["## Rank-1 PPOE against the dense PPOE (benches/rank1.rs)", ""]
    L.append("`ChainView::ppoe_rank1` (one variance per joint along its screw axis) and the dense")
    L.append("`ChainView::ppoe` on the same covariances (`screw_noise`), ns per call (criterion medians).")
    L.append("")
    L.append("| robot | scalar | dense | rank-1 | rank-1 checked | dense / rank-1 |")
    L.append("|---|---|---:|---:|---:|---:|")
    for robot, key in (("seed", "seed"), ("7-joint arm", "7dof")):
        for t in ("f64", "f32"):
            d = crit.get("rank1_%s/dense/%s" % (key, t))
            r = crit.get("rank1_%s/rank1/%s" % (key, t))
            rc = crit.get("rank1_%s/rank1_checked/%s" % (key, t))
            L.append("| %s | %s | %s | %s | %s | %s |" % (robot, t, ns(d), ns(r), ns(rc), ratio(d, r)))
    L.append("")
    return L


def render_fit(fit_text):
    rows = kv_lines(fit_text, "fit_bench")
    L = ["## Fit benchmark (ppoe-fit)", ""]
    if not rows:
        L.append("Not measured (%s)." % (step_error(fit_text) or "no `fit_bench` lines"))
        L.append("")
        return "\n".join(L) + "\n"
    L.append("`cargo run --release -p ppoe-fit --example fit_bench` (its `fit_bench` lines, as printed):")
    L.append("")
    L.append("| robot | joints | model | tracker | samples | median s | iterations | converged |")
    L.append("|---|---:|---|---|---:|---:|---:|---|")
    for r in rows:
        L.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % tuple(
            r.get(k, "?") for k in ("robot", "joints", "model", "tracker", "samples", "median_s",
                                    "iters", "converged")))
    L.append("")
    cal = kv_lines(fit_text, "fit_calibration_bench")
    if cal:
        L.append("Calibration with the noise model (`fit_campaign`, a campaign with every "
                 "systematic error at once; its `fit_calibration_bench` lines):")
        L.append("")
        L.append("| robot | joints | model | estimate | samples | median s | rounds | fits |")
        L.append("|---|---:|---|---|---:|---:|---:|---|")
        for r in cal:
            L.append("| %s | %s | %s | %s | %s | %s | %s | %s |" % tuple(
                r.get(k, "?") for k in ("robot", "joints", "model", "estimate", "samples",
                                        "median_s", "rounds", "fits")))
        L.append("")
    return "\n".join(L) + "\n"


def target_rows(crit, pin_text):
    """The budgets-table rows of the robot, Pinocchio and rank-1 targets."""
    pin = pinocchio_ns(pin_text)
    L = []

    def at_least(name, limit, val):
        L.append(at_least_row(name, limit, val))

    def at_most(name, limit, val):
        L.append("| %s | ≤ %g | %s | %s |" % (
            name, limit, "not measured" if val is None else "%.2f" % val,
            "—" if val is None else "met" if val <= limit else "**missed** by %.0f%%" % (100 * (val / limit - 1))))

    def q(a, b):
        return a / b if a is not None and b else None

    for robot, key, pkey in (("seed", "seed", "seed"), ("7-joint arm", "7dof", "arm7")):
        p64, p32 = crit.get("ppoe_%s/ours/f64" % key), crit.get("ppoe_%s/ours/f32" % key)
        at_least("host f64 PPOE vs the nalgebra port (4×4 inv), %s" % robot, 3,
                 q(crit.get("ppoe_%s/nalgebra/f64" % key), p64))
        at_least("host f64 PPOE vs the nalgebra port (closed-form inverse), %s" % robot, 3,
                 q(crit.get("ppoe_%s/nalgebra_closed/f64" % key), p64))
        at_most("host PPOE f32/f64 time, %s" % robot, 1, q(p32, p64))
        at_most("host f64 PPOE / Pinocchio FK, %s" % robot, 0.8, q(p64, pin.get(pkey)))
    pin_batch = pinocchio_batch_ns(pin_text)
    for robot, key, pkey in (("seed", "seed", "seed"), ("7-joint arm", "7dof", "arm7")):
        b = lambda i, t: batch_ns(crit, key, i, t)
        at_most("host f64 batch PPOE per configuration / Pinocchio FK, dense, %s" % robot, 1.0,
                q(b("batch", "f64"), pin_batch.get(pkey)))
        at_least("host f64 single PPOE vs the nalgebra port (4×4 inv), dense, %s" % robot, 3,
                 q(b("nalgebra", "f64"), b("single", "f64")))
        at_least("host f64 single PPOE vs the nalgebra port (closed-form inverse), dense, %s" % robot, 3,
                 q(b("nalgebra_closed", "f64"), b("single", "f64")))
        at_most("host f32/f64 time, dense, single call, %s" % robot, 1, q(b("single", "f32"), b("single", "f64")))
        at_most("host f32/f64 time, dense, batch, %s" % robot, 1, q(b("batch", "f32"), b("batch", "f64")))
    for robot, key in (("seed", "seed"), ("7-joint arm", "7dof")):
        for t in ("f64", "f32"):
            at_least("host rank-1 PPOE vs dense, %s, %s" % (robot, t), 1.5,
                     q(crit.get("rank1_%s/dense/%s" % (key, t)), crit.get("rank1_%s/rank1/%s" % (key, t))))
    return L


# The dense cases of benches/lanes_ratio.rs and the robot each names in the target rows.
DENSE_CASES = (("seed", "seed_dense"), ("7-joint arm", "arm7"),
               ("seed, batch table's configuration", "seed_batch"),
               ("7-joint arm, batch table's configuration", "arm7_batch"))


def lanes_target_rows(text):
    """Issue 28's f32-not-slower target for the single call, from the interleaved
    measurement (benches/lanes_ratio.rs: the two scalars timed round by round in one
    process), which a shared machine's drifting load disturbs less than the criterion
    medians the rows above compare (timed minutes apart)."""
    rows = lanes_ratio_rows(text)
    L = []
    for robot, case in DENSE_CASES:
        name = "host f32/f64 time, dense, single call, %s, interleaved in one process" % robot
        L.append(at_most_one_row(name, rows[case][2] if case in rows else None, 3))
    return L


# ---------------------------------------------------------------- render
def load(path):
    try:
        return json.load(open(path))
    except (OSError, ValueError):
        return None


def criterion_medians(cdir):
    """full_id -> median ns, from <cdir>/**/new/{benchmark,estimates}.json."""
    out = {}
    for b in glob.glob(os.path.join(cdir, "**", "new", "benchmark.json"), recursive=True):
        meta = json.load(open(b))
        est = json.load(open(os.path.join(os.path.dirname(b), "estimates.json")))
        out[meta["full_id"]] = est["median"]["point_estimate"]
    return out


def us(ns):
    if ns is None:
        return "—"
    v = ns / 1e3
    return "%.4f" % v if v < 0.1 else ("%.3f" % v if v < 10 else "%.1f" % v)


def ratio(a, b, fmt="%.2f×"):
    if a is None or b is None or b == 0:
        return "—"
    return fmt % (a / b)


def render(d):
    m = load(os.path.join(d, "machine.json")) or {}
    crit = criterion_medians(open(os.path.join(d, "criterion_dir")).read().strip())
    py = load(os.path.join(d, "pytransform3d.json"))
    fl = load(os.path.join(d, "flops.json"))
    cg = load(os.path.join(d, "callgrind.json"))
    fw = load(os.path.join(d, "firmware.json"))
    pin_text = read_text(os.path.join(d, "pinocchio.txt"))
    fit_text = read_text(os.path.join(d, "fit_bench.txt"))
    L = []
    p = L.append
    p("# Benchmarks")
    p("")
    p("Generated by `scripts/bench-report.sh` on %s (UTC); regenerate with that one command." % m.get("date", "?"))
    cargs = (read_text(os.path.join(d, "criterion_args")) or "?").strip()
    p("It is not run by CI: timings are noisy on shared VMs and the whole run takes several")
    p("minutes. Criterion runs once for every op (`cargo bench --bench ops --bench rank1 -- %s`;" % cargs)
    p("the default `--warm-up-time 1 --measurement-time 3` is short on purpose: medians are within")
    p("a few % of longer runs, single runs can be off by more on a busy machine); every ratio")
    p("below comes from this one run.")
    p("")
    p("**Machine** (all absolute host times): CPU %s, %s cores, %s MHz (`/proc/cpuinfo`, KVM guest);"
      % (m.get("model", "?"), m.get("cores", "?"), m.get("mhz", "?")))
    p("rustc %s; %s; load average when the run started: %s (other work on the machine inflates"
      " times; callgrind counts are unaffected)." % (m.get("rustc", "?"), m.get("git", "?"), m.get("loadavg", "?")))
    p("")
    # ---- PPOE headline
    def c(k):
        return crit.get(k)
    s64, s32 = c("ppoe_seed/ours/f64"), c("ppoe_seed/ours/f32")
    n64, n32 = c("ppoe_seed/nalgebra/f64"), c("ppoe_seed/nalgebra/f32")
    k64, k32 = c("ppoe_seed/nalgebra_closed/f64"), c("ppoe_seed/nalgebra_closed/f32")
    p("## PPOE of the seed robot (6-DOF, initial state), side by side")
    p("")
    p("| implementation | f64 µs/call | f32 µs/call | ours is faster by (f64) |")
    p("|---|---:|---:|---:|")
    p("| **ppoe** (`ChainView::ppoe`, second order; joints with their constants, as ppoe-build's tables and `Joint::from_f64` give them) | **%s** | **%s** | — |" % (us(s64), us(s32)))
    p("| ppoe, joints from `Joint::new` (displacement constants derived in every call) | %s | %s | — |" % (us(c("ppoe_seed/ours_joint_new/f64")), us(c("ppoe_seed/ours_joint_new/f32"))))
    p("| ppoe, fourth order (`ppoe_fourth_order`) | %s | %s | — |" % (us(c("ppoe_seed/ours_4th_order/f64")), us(c("ppoe_seed/ours_4th_order/f32"))))
    p("| nalgebra dense 4×4/6×6 port, transforms inverted as 4×4 matrices like pytransform3d (benches/baseline_nalgebra.rs, checked equal) | %s | %s | %s |" % (us(n64), us(n32), ratio(n64, s64)))
    p("| the same port, transforms inverted by the closed form (Rᵀ, −Rᵀp) | %s | %s | %s |" % (us(k64), us(k32), ratio(k64, s64)))
    pu = (py or {}).get("us_per_call") if py and "us_per_call" in py else None
    if pu:
        p("| pytransform3d %s example `probabilistic_forward_kinematics` (Python %s, numpy %s) | %s | — | %s |" % (
            py["pytransform3d_version"], py["python"], py["numpy_version"], us(pu["example_ppoe"] * 1e3), ratio(pu["example_ppoe"] * 1e3, s64, "%.0f×")))
        p("| lean numpy port of the same PPOE (no validation) | %s | — | %s |" % (us(pu["lean_numpy_ppoe"] * 1e3), ratio(pu["lean_numpy_ppoe"] * 1e3, s64, "%.0f×")))
    else:
        p("| pytransform3d | not measured: %s | | |" % ((py or {}).get("error", "the Python environment could not be set up")))
    if fl:
        p("| arithmetic bound (mul/add only at scalar FMA peak, see below) | %s | — | ours / bound = %s |" % (us(fl["bound_us"] * 1e3), ratio(s64, fl["bound_us"] * 1e3)))
    p("")
    p("f32 / f64 time ratio of the PPOE: %s (below 1 means f32 is faster)." % ratio(s32, s64))
    p("")
    L.extend(render_robots(crit, pin_text, (cg or {}).get("ir_per_call", {})))
    L.extend(render_batch(crit, pin_text))
    L.extend(render_alternating(read_text(os.path.join(d, "batch_alternating.txt"))))
    L.extend(render_lanes_ratio(read_text(os.path.join(d, "lanes_ratio.txt"))))
    L.extend(render_ports(read_text(os.path.join(d, "lanes_ratio.txt"))))
    L.extend(render_batch_v3(crit, d))
    L.extend(render_codegen_units(read_text(os.path.join(d, "codegen_units.txt"))))
    L.extend(render_python_batch(load(os.path.join(d, "python_batch.json")), m))
    L.extend(render_rank1(crit))
    L.extend(render_fit(fit_text).splitlines())
    # ---- chains
    p("## Cost per joint: synthetic chains (full-rank covariances), f64 and f32")
    p("")
    p("| N | f64 µs | f64 ns/joint | f32 µs | f32 ns/joint | f64 Ir/call | f64 Ir/joint |")
    p("|---:|---:|---:|---:|---:|---:|---:|")
    for n in (1, 2, 4, 8, 16, 32):
        a, b = c("ppoe_chain/f64/%d" % n), c("ppoe_chain/f32/%d" % n)
        ir = (cg or {}).get("ir_per_call", {}).get("ppoe_chain/f64/%d" % n)
        p("| %d | %s | %s | %s | %s | %s | %s |" % (
            n, us(a), "%.1f" % (a / n) if a else "—", us(b), "%.1f" % (b / n) if b else "—",
            "%.0f" % ir if ir else "—", "%.0f" % (ir / n) if ir else "—"))
    a1, a32 = c("ppoe_chain/f64/1"), c("ppoe_chain/f64/32")
    if a1 and a32 and c("ppoe_chain/f64/16"):
        marg = (a32 - c("ppoe_chain/f64/16")) / 16
        p("")
        p("Marginal cost per joint (f64, from N = 16 to 32): %.1f ns; time(32)/32 = %.1f ns, time(1)/1 = %.1f ns "
          "(the fixed cost of the last step is amortised as N grows)." % (marg, a32 / 32, a1))
    p("")
    # ---- all ops
    p("## Every operation (criterion median, µs/call) and callgrind instructions per call")
    p("")
    p("| op | f64 µs | f32 µs | f32/f64 | f64 Ir | f32 Ir |")
    p("|---|---:|---:|---:|---:|---:|")
    names = sorted({k.rsplit("/", 1)[0] for k in crit
                    if not k.startswith("ppoe_chain/") and not k.startswith("rank1_")})
    ir = (cg or {}).get("ir_per_call", {})
    for nme in names:
        a, b = c(nme + "/f64"), c(nme + "/f32")
        ia, ib = ir.get(nme + "/f64"), ir.get(nme + "/f32")
        p("| %s | %s | %s | %s | %s | %s |" % (nme, us(a), us(b), ratio(b, a),
                                             "%.0f" % ia if ia is not None else "—",
                                             "%.0f" % ib if ib is not None else "—"))
    p("")
    if cg:
        p("Ir = instructions executed per call under `valgrind --tool=callgrind` (deterministic; the")
        p("bench binary's callgrind mode runs the op %d times inside `callgrind_region`, the cost of" % cg["reps"])
        p("the dynamic call, %.0f Ir, is subtracted). Same inputs as the criterion benches." % cg["overhead"].get("f64", 0))
    else:
        p("callgrind counts: not measured (valgrind failed or is missing).")
    p("")
    if pu:
        p("Surfaces vs pytransform3d's `to_projected_ellipsoid` (same pose and covariance, factor 1):")
        p("")
        p("| n | ppoe projected f64 µs | ppoe lift f64 µs | pytransform3d µs | ours (projected) faster by |")
        p("|---:|---:|---:|---:|---:|")
        for n in (20, 50):
            a = c("surface_pytransform3d_n%d/f64" % n)
            p("| %d | %s | %s | %s | %s |" % (n, us(a), us(c("surface_lift_n%d/f64" % n)), us(pu["to_projected_ellipsoid_n%d" % n] * 1e3),
                                           ratio(pu["to_projected_ellipsoid_n%d" % n] * 1e3, a, "%.0f×")))
        p("")
    # ---- bound
    if fl:
        t, pj = fl["total"], fl["per_joint"]
        p("## Arithmetic bound")
        p("")
        p("`scripts/flops.py` counts the PPOE's floating-point operations from the source (hand count,")
        p("documented per function there): per joint %d multiplies + %d adds, %d divisions, %d square root, %d sin_cos;"
          % (pj["mul"], pj["add"], pj["div"], pj["sqrt"], pj["sin_cos"]))
        p("plus %d + %d after the loop (summing the %d f64 SIMD lanes of the accumulator; a last incomplete"
          " group is padded with zeros, its empty lanes counted as computed). 6-DOF total: **%d multiplies + %d adds = %d flops**,"
          % (fl["tail"]["mul"], fl["tail"]["add"], fl.get("lanes", 1), t["mul"], t["add"], fl["flops_mul_add"]))
        p("%d divisions, %d square roots, %d sin_cos." % (t["div"], t["sqrt"], t["sin_cos"]))
        p("")
        p("Assumed scalar peak: %d FMA per cycle (two FMA pipes, as Zen and Intel cores since Haswell have; a fused" % fl["fma_per_cycle"])
        p("multiply-add covers one multiply and one add) at %.3f GHz (`cpu MHz` of /proc/cpuinfo; the" % fl["ghz"])
        p("guest does not expose boost clocks). max(mul, add) / %d = %.0f cycles = **%.3f µs**; division," % (fl["fma_per_cycle"], fl["bound_cycles"], fl["bound_us"]))
        p("sqrt and sin_cos are not included, so the true floor is higher. The bound is scalar: SIMD")
        p("code can beat it, so ours/bound < 1 is possible. Measured f64: %s µs = %s the bound." % (us(s64), ratio(s64, fl["bound_us"] * 1e3)))
        p("")
    # ---- firmware
    opt = "?"
    fw_toml = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "firmware", "Cargo.toml")
    for line in open(fw_toml).read().splitlines():
        if line.startswith("opt-level"):
            opt = line.split("=")[1].split("#")[0].strip().strip('"')
            break
    p(f"## Cortex-M4F (thumbv7em-none-eabihf, QEMU mps2-an386, opt-level {opt}, LTO)")
    p("")
    if fw and "ppoe_insns" in fw:
        pi = fw["ppoe_insns"]
        p("From `scripts/firmware.sh` (this run): instructions from SysTick under `-icount shift=0`")
        p("(1 tick = 40 instructions; PPOE averaged over 16 (f32) / 4 (f64) calls, the other ops over 64).")
        p("Same inputs as the host: the seed robot's initial state (firmware case 0), and for the ops")
        p("the same ξ, transforms and covariance as benches/ops.rs.")
        p("")
        p("| op | f32 instructions | f64 instructions | host f64 Ir (x86-64) |")
        p("|---|---:|---:|---:|")
        p("| PPOE, 6-DOF seed | %d | %d | %s |" % (pi["f32"], pi["f64"], "%.0f" % ir["ppoe_seed/ours/f64"] if "ppoe_seed/ours/f64" in ir else "—"))
        for op, v in (fw.get("op_insns") or {}).items():
            p("| %s | %.0f | %.0f | %s |" % (op, v["f32"], v["f64"], "%.0f" % ir[op + "/f64"] if op + "/f64" in ir else "—"))
        p("")
    else:
        p("Firmware numbers: not available (scripts/firmware.sh did not run or failed; see its log).")
        p("")
    if fw and "path" in fw:
        p("Code size (flash bytes, `arm-none-eabi-nm -S` of the M4F firmware): ppoe's own functions")
        p("(symbols under `ppoe::`, after LTO inlining, all of them) %d B; the PPOE path = `ppoe_seed_f32` and every" % fw["own_bytes"])
        p("function it calls transitively (objdump call graph):")
        p("")
        p("| path | bytes | of which ppoe's own | functions | largest |")
        p("|---|---:|---:|---:|---|")
        for t in ("f32", "f64"):
            q = fw["path"][t]
            p("| PPOE %s | %d | %d | %d | %s |" % (t, q["bytes"], q.get("ppoe_bytes", 0), q["functions"], ", ".join("`%s` %d" % (re.sub(r"\[[0-9a-f]{16}\]", "", n)[:70], s) for n, s in q["largest"][:4])))
        p("| both | %d | | | |" % fw["path_both_bytes"])
        p("")
        p("Whole firmware (with test harness, float formatting, semihosting): text %d B, data %d B, bss %d B."
          % (fw["elf_size"]["text"], fw["elf_size"]["data"], fw["elf_size"]["bss"]))
        p("")
        p("Heap: %s" % ("zero — no allocator symbol (`__rust_alloc`, `__rg_alloc`, `malloc`, …) is linked." if not fw["alloc_symbols"] else "allocator symbols found: " + ", ".join(fw["alloc_symbols"])))
        if "stack" in fw:
            p("Stack high-water mark of one PPOE call (painted stack): f32 %d B, f64 %d B." % (fw["stack"]["f32"], fw["stack"]["f64"]))
        p("")
        f32p = fw["path"]["f32"]
        if f32p["soft_f64_calls"] or f32p["mem_calls"]:
            p("Reachable from `ppoe_seed_f32` in the call graph: soft-float f64 helpers %s; memory helpers %s." % (
                ", ".join(f32p["soft_f64_calls"]) or "none", ", ".join(f32p["mem_calls"]) or "none"))
            p("")
    # ---- budgets
    p("## Budgets and targets")
    p("")
    p("| budget / target | value | measured | status |")
    p("|---|---:|---:|---|")

    def row(name, limit, val, unit, fmt="%.0f"):
        if val is None:
            p("| %s | %s %s | not measured | — |" % (name, fmt % limit, unit))
            return
        ok = val <= limit
        p("| %s | ≤ %s %s | %s %s | %s |" % (name, fmt % limit, unit, fmt % val, unit,
                                        "met (%.0f%% of it)" % (100 * val / limit) if ok else "**missed** by %s %s (%.1f×)" % (fmt % (val - limit), unit, val / limit)))
    row("M4F f32 6-DOF PPOE (issue 5)", 8000, fw and fw.get("ppoe_insns", {}).get("f32"), "instructions")
    row("M4F PPOE path code, f32 (issue 5)", 16384, fw and fw.get("path", {}).get("f32", {}).get("bytes"), "B")
    row("M4F PPOE path code, f32 + f64 (informative)", 16384, fw and fw.get("path_both_bytes"), "B")
    row("M4F stack of a PPOE call, f32 (issue 5)", 2048, fw and fw.get("stack", {}).get("f32"), "B")
    row("M4F stack of a PPOE call, f64 (informative)", 2048, fw and fw.get("stack", {}).get("f64"), "B")
    row("host f64 6-DOF PPOE (issue 6)", 0.3, s64 and s64 / 1e3, "µs", "%.3f")
    su = c("surface_pytransform3d_n50/f64")
    row("host surface n = 50, projected (issue 6)", 40, su and su / 1e3, "µs", "%.1f")
    sl = c("surface_lift_n50/f64")
    row("host surface n = 50, lift (issue 6)", 40, sl and sl / 1e3, "µs", "%.1f")
    def at_least(name, limit, val):
        if val is None:
            p("| %s | ≥ %g× | not measured | — |" % (name, limit))
        else:
            p("| %s | ≥ %g× | %s× | %s |" % (name, limit, "%.0f" % val if val >= 100 else "%.2f" % val,
                                              "met" if val >= limit else
                                              "**missed** (%.0f%% of it)" % (100 * val / limit)))
    pu64 = ((py or {}).get("us_per_call") or {}).get("example_ppoe")
    at_least("host f64 PPOE vs pytransform3d's example (issue 6)", 7000,
             pu64 * 1e3 / s64 if pu64 and s64 else None)
    L.extend(target_rows(crit, pin_text))
    L.extend(lanes_target_rows(read_text(os.path.join(d, "lanes_ratio.txt"))))
    L.extend(port_target_rows(read_text(os.path.join(d, "lanes_ratio.txt"))))
    L.extend(alternating_target_rows(read_text(os.path.join(d, "batch_alternating.txt"))))
    if a1 and a32:
        p("| constant cost per joint (issue 6) | time(N)/N flat | %.1f ns (N=1) … %.1f ns (N=32) | see the chain table |" % (a1, a32 / 32))
    p("")
    p("### Notes on the targets (measured facts of this run)")
    p("")
    irc = (cg or {}).get("ir_per_call", {})
    if fw and "ppoe_insns" in fw and fw.get("op_insns"):
        e = fw["op_insns"].get("se3_exp", {})
        pi = fw["ppoe_insns"]
        p("- M4F f32 PPOE: %d instructions, ≈ %.0f per joint (one f32 `se3::exp` alone: %.0f). The M4F"
          " has no SIMD for floats, so the PPOE's lane width (private, `lanes` in src/ppoe/schedule.rs) is 1"
          " there: one structured transport at"
          " a time, the same operations as on the host." % (pi["f32"], pi["f32"] / 6, e.get("f32", 0)))
        for f, calls in (fw.get("direct_calls") or {}).items():
            p("  `%s` calls: %s." % (f, ", ".join("%s ×%d" % (k, v) for k, v in sorted(calls.items()))))
        p("- M4F f64: the core has no double-precision FPU, every f64 operation is a software call"
          " (%d instructions per PPOE); f64 is not a target there." % pi["f64"])
    if pu64 and s64:
        fk64 = c("fk_seed/ours/f64")
        line = ("- pytransform3d: its example takes %s µs per call in this run (the issue measured 2.29 ms"
                " on its machine, which set the 7,000×). Ours is %.0f× faster" % (us(pu64 * 1e3), pu64 * 1e3 / s64))
        line += " (target 7,000×: %s)." % ("met" if pu64 * 1e3 / s64 >= 7000 else "missed by %.0f%%" % (100 * (1 - pu64 * 1e3 / s64 / 7000)))
        if pu64 * 1e3 / s64 < 7000:
            need = pu64 * 1e3 / 7000
            line += " 7,000× would need %s µs per PPOE here" % us(need)
            if fk64 and fk64 >= need:
                line += ("; the rigid forward kinematics alone (six sin/cos and the serial product)"
                         " takes %s µs, so even a free covariance would reach only %.0f×." % (us(fk64), pu64 * 1e3 / fk64))
            elif fk64:
                line += ("; the rigid forward kinematics alone takes %s µs of our %s µs, so the six"
                         " covariance transports would have to take %s µs instead of %s µs"
                         % (us(fk64), us(s64), us(need - fk64), us(s64 - fk64)))
                if fl and fl.get("ghz"):
                    # Their multiplies in 2-lane SIMD (SSE2) at fma_per_cycle per cycle.
                    tm = 6 * fl["pieces"]["transport"]["mul"]
                    simd_ns = tm / fl.get("lanes", 2) / fl["fma_per_cycle"] / fl["ghz"]
                    line += (", while their %d multiplies need %s µs even two to a register at"
                             " %d per cycle" % (tm, us(simd_ns), fl["fma_per_cycle"]))
                line += "."
            else:
                line += "."
        p(line)
    if s64:
        fk = c("fk_seed/ours/f64")
        line = "- Host f64 PPOE: %s µs against the 0.3 µs target (%s)." % (
            us(s64), "met" if s64 <= 300 else "missed by %.0f%%" % (100 * (s64 / 300 - 1)))
        if fk:
            line += (" The rigid forward kinematics alone (`fk_seed`: the same six displacements and"
                     " their serial product) takes %s µs, %.0f%% of it; the covariance part (six structured"
                     " transports, computed two at a time in SIMD lanes) the rest." % (us(fk), 100 * fk / s64))
        if fl:
            line += (" The scalar mul/add bound of the %d counted flops is %.3f µs on this %.2f GHz guest"
                     " (SIMD code may go below it)." % (fl["flops_mul_add"], fl["bound_us"], fl["ghz"]))
        p(line)
        p("- How the PPOE got here (each step kept only with the golden tests green at unchanged"
          " tolerances; `git log` has the before/after figures): accumulation in the tip frame from"
          " the tip backwards (no transport after the loop, lever arms from each joint to the tip),"
          " a shear-first structured transport accumulated into one triangle (no 6×6 temporaries),"
          " independent transports packed into SIMD lanes (the private lane width, `lanes` in"
          " src/ppoe/schedule.rs: one 128-bit register on SSE2/NEON, 2 f64 lanes, 4 f32 lanes except"
          " on x86, where f32 runs two), the joints taken in groups whose congruences are written"
          " into the lanes of packs as they are made and transported one group later (gathered from"
          " registers they cost loads, shuffles and spills; transported at once, the packs were"
          " loaded right after their lanes were stored and waited on store forwarding), per-joint displacement constants computed once (`JointConstants`:"
          " ppoe-build's tables carry them; a joint's displacement is then one sin/cos, 19"
          " multiplies and 17 adds), sin/cos inlined (f64: libm's own kernel, the same bits;"
          " a call clobbered every SSE register in the loop), and the f32 sin/cos polynomials"
          " by Estrin's scheme with `(x, 1)` for |x| ≤ 2⁻¹² (their own bits there): a joint's"
          " sin/cos heads its displacement's chain, and this shortens it. Tried without a measurable gain"
          " and dropped: computing the displacements of up to 8 joints ahead of the serial"
          " product so that their sin/cos latencies overlap; a branch-free quadrant selection in"
          " the f32 sin/cos (slower: the quadrant branch predicts well); the serial product on"
          " rows packed as 4-lane vectors (slower: packing costs more than it saves); gathering"
          " only the covariance entries the transport reads (no change); two f32 lanes gathered"
          " from registers (computed in 4-lane registers whose other lanes held leftovers that"
          " underflowed into subnormals; loaded from packs in memory, those lanes hold zeros:"
          " tests/subnormal_lanes.rs checks the CPU's subnormal flags); two f32 joints in four"
          " lanes whose other two are zero (slower); the rows of one"
          " transport's matrices in 4-lane packs (`Ad·Σ` row by row, then `(Ad·Σ)·Adᵀ`; the"
          " optimiser scalarised the packs and regrouped them with shuffles, more instructions)."
          " f32 single calls run two lanes on x86: four lanes executed fewer instructions but"
          " ran slower (the `lanes_ratio` section of this report times every width)."
          " `RUSTFLAGS=\"--cfg ppoe_bench_lanes\" cargo bench --bench lanes_ratio` times every lane"
          " width of both scalars interleaved in one process (its own section of this report);"
          " `LANES_RATIO_FTZ=1` (flush-to-zero) shows what subnormals cost, `LANES_RATIO_FLAGS=1`"
          " which widths raise the subnormal flags.")
        nn64, nn32 = c("ppoe_seed/ours_joint_new/f64"), c("ppoe_seed/ours_joint_new/f32")
        if nn64:
            p("- Joints built with `Joint::new` (a `const fn`, which cannot compute the displacement"
              " constants) derive them in every call: %s µs (f64) and %s µs (f32) instead of %s and"
              " %s. `Joint::prepared()` or `Joint::from_f64` at start-up removes the difference;"
              " ppoe-build's tables need nothing." % (us(nn64), us(nn32), us(s64), us(s32)))
    fr32, fo32 = c("fk_seed/rounded_only/f32"), c("fk_seed/ours/f32")
    if fr32 and fo32:
        p("- Subnormals: the seed URDF's rpy angles leave entries of −1.9·10⁻²³ in two screw axes"
          " and the home pose. Rounded to f32 they are normal, but their products are subnormal,"
          " which x86 cores compute on a slow path. With those entries (`fk_seed/rounded_only`,"
          " displacement constants computed the same way) the f32 forward kinematics takes %s µs,"
          " %.2f× the %s µs of the chain as ppoe-build converts it (`Joint::from_f64` /"
          " `Transform::from_f64` zero the elements below ε²·max of their vector; no result moves"
          " by more than ε² relative). f64: %s vs %s µs.%s" % (
              us(fr32), fr32 / fo32, us(fo32), us(c("fk_seed/rounded_only/f64")),
              us(c("fk_seed/ours/f64")),
              "" if fr32 / fo32 > 1.1 else
              " With the products of the axis computed once per joint (`JointConstants`) the"
              " per-call arithmetic no longer meets them; the zeroing stays as a guard."))
    if s32 and s64:
        e64, e32 = c("so3_exp/f64"), c("so3_exp/f32")
        line = "- Host f32/f64 PPOE time: %.2f." % (s32 / s64)
        if e64 and e32:
            line += " One `so3::exp` takes %.1f ns in f32 and %.1f ns in f64" % (e32, e64)
            if e32 > 1.2 * e64:
                line += (": the f32 sin/cos is our Cody–Waite reduction + polynomial, written for the"
                         " M4F (libm's `sinf` computes in f64, which the M4F emulates); on this core its"
                         " latency exceeds that of libm's f64 `sincos` kernel.")
            else:
                line += (" (the f32 sin/cos skips the range reduction for |x| ≤ π/4, like libm's f64"
                         " kernel), so sin/cos does not explain a gap.")
        i64, i32 = irc.get("ppoe_seed/ours/f64"), irc.get("ppoe_seed/ours/f32")
        if i64 and i32:
            line += " Instructions per call (callgrind): f32 %.0f, f64 %.0f." % (i32, i64)
        c8_64, c8_32 = c("ppoe_chain/f64/8"), c("ppoe_chain/f32/8")
        c32_64, c32_32 = c("ppoe_chain/f64/32"), c("ppoe_chain/f32/32")
        if c8_64 and c8_32 and c32_64 and c32_32:
            line += (" On the synthetic chains f32/f64 is %.2f (N = 8) and %.2f (N = 32)."
                     % (c8_32 / c8_64, c32_32 / c32_64))
        if s32 > s64:
            fk32 = c("fk_seed/ours/f32")
            fk64 = c("fk_seed/ours/f64")
            if fk32 and fk64:
                line += (" The rigid part alone: f32 %s µs, f64 %s µs; the rest (the transports):"
                         " f32 %s µs, f64 %s µs." % (us(fk32), us(fk64), us(s32 - fk32), us(s64 - fk64)))
            line += (" On x86 the single call runs f32 transports one at a time and f64 two"
                     " side by side (src/ppoe/schedule.rs says why; the rigid part is scalar).")
        p(line)
    p("")
    # ---- firmware targets: kept from BENCHMARKS.md as it was (it names its own run)
    kept = (read_text(os.path.join(d, "firmware_targets.md")) or "").strip()
    # The sections after it are this run's (the Python package's batch is rendered above).
    kept = kept.split("\n## Python package")[0].strip()
    if kept:
        p(kept)
    else:
        p("## Firmware targets (scripts/firmware.sh)")
        p("")
        p("No firmware-targets section in the previous BENCHMARKS.md to keep; run scripts/firmware.sh.")
    fresh = read_text(os.path.join(d, "firmware_figures_this_run.md"))
    if fresh:
        p("")
        p("### Firmware figures of this run (scripts/firmware.sh, `firmware-figures.md`)")
        p("")
        p(fresh.strip())
    return "\n".join(L) + "\n"


def main():
    cmd = sys.argv[1]
    if cmd == "callgrind":
        cmd_callgrind(sys.argv[2], sys.argv[3])
    elif cmd == "firmware":
        cmd_firmware(sys.argv[2], sys.argv[3])
    elif cmd == "render":
        sys.stdout.write(render(sys.argv[2]))
    elif cmd == "pinocchio-ir":
        cmd_pinocchio_ir(sys.argv[2])
    elif cmd == "selftest":
        selftest()
    else:
        sys.exit("unknown command " + cmd)


if __name__ == "__main__":
    main()
