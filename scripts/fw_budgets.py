#!/usr/bin/env python3
"""Firmware figures against their budgets (scripts/firmware.sh runs this).

  fw_budgets.py BUDGETS.toml [--markdown OUT.md] [--json OUT.json] RUN...
      RUN = LABEL:ELF:LOG:PER_TICK  (LOG: the firmware's QEMU output; PER_TICK the
              instructions per counter tick under -icount, 0 if the board's counter does
              not count instructions)

For each run it reads from the log the instructions per 6-DOF PPOE call (counter ticks x
PER_TICK, under `qemu -icount shift=0`) and the stack high-water of one call, and from the ELF the
PPOE-path code size: the bytes of every function reachable by direct calls or branches from
the firmware's `ppoe_seed_f32` / `ppoe_seed_f64` (llvm-objdump), so what a user's firmware
links for one PPOE call, without the test harness. The same three figures of the rank-one
PPOE (`ppoe_rank1`, one variance per joint; log lines "per rank-1 PPOE call", roots
`ppoe_seed_rank1_f32` / `_f64`) are the keys with `rank1_` after the kind.

Every figure with a budget in BUDGETS.toml (table [LABEL], keys insns_f32, insns_f64,
path_f32, path_f64, stack_f32, stack_f64, and insns_rank1_f32 ... stack_rank1_f64) is printed
against it; the exit status is 1 if any exceeds its budget by more than the file's `slack`
(a fraction; 0.10), or if a budgeted figure is missing. Figures without a budget are printed
as "no budget". The Markdown output has the figures table and a rank-one vs dense table
(instructions and their ratio, code size, stack).

  fw_budgets.py --compare-bits LOG_A LOG_B TOL
      The f32 results of two runs of the same cases ("f32 bits" lines): max relative
      difference `max|a-b| / max(1, max|b|)` over pose and covariance; exit 1 above TOL.
"""
import json
import os
import re
import struct
import subprocess
import sys
import tomllib

DENSE = ("insns_f32", "insns_f64", "path_f32", "path_f64", "stack_f32", "stack_f64")
RANK1 = tuple(k.replace("_", "_rank1_") for k in DENSE)
FIGURES = DENSE + RANK1
UNITS = {"insns": "insns", "path": "B", "stack": "B"}


def sh(*a):
    return subprocess.run(list(a), capture_output=True, text=True, check=True).stdout


def is_arm(elf):
    with open(elf, "rb") as f:
        head = f.read(20)
    return head[18] == 0x28  # e_machine EM_ARM (else RISC-V here)


def text_symbols(elf, by_addr=False):
    """mangled name -> size (or address -> name) of function symbols."""
    out = {}
    for line in sh("llvm-nm", "--size-sort", "-S", elf).splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[2] in "tTwW":
            if by_addr:
                out[int(parts[0], 16) & ~1] = parts[3]
            else:
                out[parts[3]] = int(parts[1], 16)
    return out


def call_graph(elf):
    """function -> callees: every `<symbol>` (no offset) an instruction names (ARM:
    GNU objdump, which names branch targets; llvm-objdump 14 names thumb targets by their
    mapping symbols), and on RISC-V the targets of `auipc`+`jalr`/`jr` pairs, resolved by
    address (llvm-objdump does not name them)."""
    arm = is_arm(elf)
    tool = "arm-none-eabi-objdump" if arm else "llvm-objdump"
    by_addr = {} if arm else text_symbols(elf, by_addr=True)
    graph, cur, regs = {}, None, {}
    for line in sh(tool, "-d", "--no-show-raw-insn", elf).splitlines():
        m = re.match(r"^[0-9a-f]+ <([^>]+)>:$", line)
        if m and not m.group(1).startswith(".L"):  # local labels stay in their function
            cur, regs = m.group(1), {}
            graph[cur] = set()
            continue
        if cur is None:
            continue
        for callee in re.findall(r"<([^>+$]+)>", line):
            if callee != cur:
                graph[cur].add(callee)
        if arm:
            continue
        m = re.match(r"^\s*([0-9a-f]+):\s+(\w+)\s+(.*)$", line)
        if not m:
            continue
        pc, op, args = int(m.group(1), 16), m.group(2), m.group(3)
        if op == "auipc":
            reg, imm = [x.strip() for x in args.split(",")]
            imm = int(imm, 0) & 0xFFFFF
            regs[reg] = pc + ((imm - (1 << 20) if imm >> 19 else imm) << 12)
        elif op in ("jalr", "jr"):
            t = re.search(r"(-?\d+)\((\w+)\)", args)
            if t and t.group(2) in regs:
                target = by_addr.get((regs[t.group(2)] + int(t.group(1))) & ~1)
                if target and target != cur:
                    graph[cur].add(target)
    return graph


def path_bytes(elf, root):
    syms, graph = text_symbols(elf), call_graph(elf)
    if root not in graph:
        return None
    seen, todo = set(), [root]
    while todo:
        f = todo.pop()
        if f in seen:
            continue
        seen.add(f)
        todo.extend(graph.get(f, ()))
    return sum(syms.get(f, 0) for f in seen)


def log_figures(log, per_tick):
    txt = open(log, errors="replace").read()
    out = {}
    for what, key in (("PPOE", ""), ("rank-1 PPOE", "rank1_")):
        m = re.search(rf"^(.+) per {what} call: f32 (\d+) f64 (\d+)", txt, re.M)
        if m and per_tick > 0:
            out[f"insns_{key}f32"] = int(m.group(2)) * per_tick
            out[f"insns_{key}f64"] = int(m.group(3)) * per_tick
        m = re.search(rf"^stack per {what} call[^:]*: f32 (\d+) B, f64 (\d+) B", txt, re.M)
        if m:
            out[f"stack_{key}f32"], out[f"stack_{key}f64"] = int(m.group(1)), int(m.group(2))
    return out


def run_figures(elf, log, per_tick):
    fig = log_figures(log, per_tick) if os.path.exists(log) else {}
    if os.path.exists(elf):
        for key in ("", "rank1_"):
            for t in ("f32", "f64"):
                b = path_bytes(elf, f"ppoe_seed_{key}{t}")
                if b is not None:
                    fig[f"path_{key}{t}"] = b
    return fig


def check(budgets, runs):
    slack = float(budgets.get("slack", 0.10))
    failed, rows = [], []
    for label, fig in runs:
        bud = budgets.get(label, {})
        for key in FIGURES:
            val, lim = fig.get(key), bud.get(key)
            unit = UNITS[key.split("_")[0]]
            if lim is None:
                status = "no budget"
            elif val is None:
                status = "MISSING"
                failed.append(f"{label} {key}")
            elif val > lim * (1 + slack):
                status = f"OVER BUDGET ({val / lim:.2f}x > {1 + slack:.2f}x)"
                failed.append(f"{label} {key}")
            else:
                status = f"ok ({val / lim:.2f}x)"
            if val is None and lim is None:
                continue
            shown = "-" if val is None else str(val)
            print(f"  {label:<30} {key:<16} {shown:>9} {unit:<5} budget {lim if lim is not None else '-':>9}  {status}")
            rows.append((label, key, val, lim))
    return failed, rows


def ratio(fig, key):
    """`rank-1 / dense` of figure `key` ("insns_f32", ...) as text, "n/a" if either is missing."""
    a, b = fig.get(key.replace("_", "_rank1_")), fig.get(key)
    return "n/a" if a is None or not b else f"{a / b:.2f}"


def rank1_lines(runs):
    """The rank-one vs dense table (targets with a rank-one figure only)."""
    lines = [
        "| target | f32 insns dense | f32 insns rank-1 | ratio | f64 insns dense | f64 insns rank-1"
        " | ratio | f32 path B dense / rank-1 | f64 path B dense / rank-1 | f32 stack B dense / rank-1"
        " | f64 stack B dense / rank-1 |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for label, fig in runs:
        if not any(k in fig for k in RANK1):
            continue
        cell = lambda k: str(fig[k]) if k in fig else "n/a"
        pair = lambda k: cell(k) + " / " + cell(k.replace("_", "_rank1_"))
        cells = [cell("insns_f32"), cell("insns_rank1_f32"), ratio(fig, "insns_f32"),
                 cell("insns_f64"), cell("insns_rank1_f64"), ratio(fig, "insns_f64"),
                 pair("path_f32"), pair("path_f64"), pair("stack_f32"), pair("stack_f64")]
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    return lines


def markdown(runs, budgets, out):
    lines = [
        "| target | core, QEMU board | f32 PPOE insns | f64 PPOE insns | f32 path B | f64 path B | f32 stack B | f64 stack B |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for label, fig in runs:
        desc = budgets.get(label, {}).get("describe", "")
        cells = [str(fig[k]) if k in fig else "n/a" for k in DENSE]
        lines.append(f"| {label} | {desc} | " + " | ".join(cells) + " |")
    lines += ["", "Rank-one PPOE (`ppoe_rank1`, one variance per joint value) against the dense"
              " PPOE, same joint values (firmware case 0); ratio = rank-1 / dense:", ""]
    lines += rank1_lines(runs)
    with open(out + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(out + ".tmp", out)


def f32_bits(log):
    out = {}
    for m in re.finditer(r"^f32 bits (\w+): \[([0-9a-f, ]+)\]", open(log).read(), re.M):
        words = [int(w, 16) for w in m.group(2).split(",")]
        out[m.group(1)] = [struct.unpack("<f", struct.pack("<I", w))[0] for w in words]
    return out


def rel(a, b):
    num = max(abs(x - y) for x, y in zip(a, b))
    return num / max(1.0, max(abs(y) for y in b))


def compare_bits(log_a, log_b, tol):
    a, b = f32_bits(log_a), f32_bits(log_b)
    if not a or a.keys() != b.keys():
        print(f"f32 cross-check: cases differ or missing ({sorted(a)} vs {sorted(b)})")
        return 1
    worst, same = 0.0, 0
    for name in a:
        if a[name] == b[name]:
            same += 1
        worst = max(worst, rel(a[name][:16], b[name][:16]), rel(a[name][16:], b[name][16:]))
    ok = worst <= tol
    print(f"f32 cross-check: {len(a)} cases, {same} bit-identical, worst rel. difference "
          f"{worst:.2e} (tol {tol:.0e}): {'ok' if ok else 'FAILED'}")
    return 0 if ok else 1


def main(argv):
    if len(argv) == 4 and argv[0] == "--compare-bits":
        return compare_bits(argv[1], argv[2], float(argv[3]))
    budgets = tomllib.load(open(argv[0], "rb"))
    md = js = None
    specs = []
    it = iter(argv[1:])
    for a in it:
        if a == "--markdown":
            md = next(it)
        elif a == "--json":
            js = next(it)
        else:
            specs.append(a)
    runs = []
    for spec in specs:
        label, elf, log, per_tick = spec.split(":")
        runs.append((label, run_figures(elf, log, int(per_tick))))
    print(f"---- firmware budgets ({os.path.basename(argv[0])}; fail above budget x {1 + float(budgets.get('slack', 0.1)):.2f})")
    failed, _ = check(budgets, runs)
    for label, fig in runs:
        if "insns_rank1_f32" in fig or "insns_rank1_f64" in fig:
            print(f"  {label:<30} rank-1 vs dense instructions: f32 {fig.get('insns_rank1_f32', '-')}"
                  f" vs {fig.get('insns_f32', '-')} ({ratio(fig, 'insns_f32')}x),"
                  f" f64 {fig.get('insns_rank1_f64', '-')} vs {fig.get('insns_f64', '-')}"
                  f" ({ratio(fig, 'insns_f64')}x)")
    if md:
        markdown(runs, budgets, md)
    if js:
        with open(js + ".tmp", "w") as f:
            json.dump(dict(runs), f, indent=1)
        os.replace(js + ".tmp", js)
    if failed:
        print("budgets: FAILED: " + ", ".join(failed))
        return 1
    print("budgets: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
