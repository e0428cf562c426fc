#!/usr/bin/env python3
"""Floating-point operation count of ppoe's PPOE (ChainView::ppoe, Convention::Right).

A hand count of the source as written (src/ppoe/schedule.rs `ppoe_lanes`, `Sums::total`;
src/se3/congruence.rs `Congruence::of_inverse`, `transport_lower`, `sandwich_add`,
`cross_component`; src/joint.rs `JointConstants::displacement`; src/se3/mod.rs
`Transform::compose`), for joints
with their displacement constants (ppoe-build's tables, `Joint::from_f64`,
`Joint::prepared`), counting multiplies and adds/subtracts separately (negations,
transposes, clipping compares, copies and the lane packing: 0), and division, square root
and sin_cos apart. Update the table below when those functions change.

Usage: python3 scripts/flops.py [N] [--ghz G] [--fma-per-cycle K] [--lanes W] -> JSON
"""

import json
import sys

# (multiplies, adds) per piece.
MAT3_MUL = (27, 18)  # 3x3 * 3x3
MAT3_VEC = (9, 6)  # 3x3 * 3-vector
# sandwich_add: per column j, y = X r_j (9 mul, 6 add), then r_i . y (3 mul, 2 add) for
# the 3 (general) or 3 - j (lower triangle) rows i, each added to the accumulator (1 add).
SANDWICH_FULL = (27 + 27, 18 + 18 + 9)
SANDWICH_SYM = (27 + 18, 18 + 12 + 6)

PIECES = {
    # JointConstants::displacement: t = theta*|w| (1 mul), sin_cos, 1 - cos (1 add); the
    # rotation from the constant axis products: 3 diagonal entries 1 - (1-c)*d_i (1 mul,
    # 1 add), 6 off-diagonal entries (1-c)*p_ij +- s*x_k from 3 + 3 products (1 add
    # each); t - s (1 add); the translation s*v + (1-c)*(x cross v) + (t-s)*(x.v)x from
    # constant vectors (9 mul, 6 add).
    "exp": {
        "mul": 1 + (3 + 3 + 3) + 9,
        "add": 1 + (3 + 6) + 1 + 6,
        "div": 0,
        "sqrt": 0,
        "sin_cos": 1,
    },
    # g = D * g: R1 R2, R1 p2 + p1.
    "compose": {
        "mul": MAT3_MUL[0] + MAT3_VEC[0],
        "add": MAT3_MUL[1] + MAT3_VEC[1] + 3,
    },
    # transport_lower with Congruence::of_inverse (R^T, q = -p: no arithmetic): the shear,
    # E = Q A + B^T (9 entries: 2 mul, 1 sub, 1 add) and the lower-right triangle
    # (6 entries: two cross components, 4 mul 2 sub, and 2 add); then the block rotations
    # R A R^T, R (lower right) R^T (lower triangles) and R E R^T (full), each accumulated.
    "transport": {
        "mul": 18 + 24 + 2 * SANDWICH_SYM[0] + SANDWICH_FULL[0],
        "add": 18 + 24 + 2 * SANDWICH_SYM[1] + SANDWICH_FULL[1],
    },
}


def add(*ds):
    out = {}
    for d in ds:
        for k, v in d.items():
            out[k] = out.get(k, 0) + v
    return out


def count(n, lanes=2):
    p = PIECES
    per_joint = add(p["exp"], p["compose"], p["transport"])
    # After the loop: the W lanes of the 36 accumulated entries are summed from zero (W
    # adds each, `Sums::total`). A last incomplete group of `filled` joints runs packed,
    # its empty lanes counted as computed, when W = 2 or it fills more than half of the W
    # lanes (src/ppoe/schedule.rs, `Sums::add`); otherwise its joints run one lane at a
    # time and nothing is padded.
    filled = n % lanes
    pad = lanes - filled if filled and (lanes == 2 or 2 * filled > lanes) else 0
    tail = add(*([p["transport"]] * pad), {"mul": 0, "add": 36 * lanes})
    total = add(*([per_joint] * n), tail)
    return per_joint, tail, total


def main():
    args = sys.argv[1:]
    n = 6
    ghz = None
    fma_per_cycle = 2
    lanes = 2
    i = 0
    while i < len(args):
        if args[i] == "--ghz":
            ghz = float(args[i + 1])
            i += 2
        elif args[i] == "--lanes":
            lanes = int(args[i + 1])
            i += 2
        elif args[i] == "--fma-per-cycle":
            fma_per_cycle = int(args[i + 1])
            i += 2
        else:
            n = int(args[i])
            i += 1
    per_joint, tail, total = count(n, lanes)
    flops = total["mul"] + total["add"]
    # With every add fused into a multiply (FMA), the multiplies alone need
    # mul / fma_per_cycle cycles on the FMA pipes; more adds than multiplies would need
    # add / fma_per_cycle. So the mul/add arithmetic needs >= max(mul, add) / K cycles.
    cycles = max(total["mul"], total["add"]) / fma_per_cycle
    out = {
        "n": n,
        "lanes": lanes,
        "per_joint": per_joint,
        "tail": tail,
        "total": total,
        "flops_mul_add": flops,
        "fma_per_cycle": fma_per_cycle,
        "bound_cycles": cycles,
        "pieces": PIECES,
    }
    if ghz:
        out["ghz"] = ghz
        out["bound_us"] = cycles / (ghz * 1e3)
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
