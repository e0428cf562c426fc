#!/usr/bin/env python3
"""Floating-point operation count of ppoe's PPOE (ChainRef::ppoe, Convention::Right).

A hand count of the source as written (src/chain.rs `ppoe`, src/se3.rs `exp`,
`Transform::mul`, `inverse`, `transport_covariance`, `sym_sandwich`, `cross_columns`,
src/so3.rs `ExpCoefficients::new` (non-series branch), `i_plus_aw_bw2`), counting
multiplies and adds/subtracts separately (negations, clipping compares, copies: 0), and
division, square root and sin_cos apart. Common subexpressions the compiler sees after
inlining (the products w_i w_j, b·xy, a·z, ... shared by R and J in se3::exp) are counted
once. Update the table below when those functions change.

Usage: python3 scripts/flops.py [N] [--ghz G] [--fma-per-cycle K]  -> JSON on stdout
"""

import json
import sys

# (multiplies, adds) per piece.
MAT3_MUL = (27, 18)  # 3x3 * 3x3
MAT3_VEC = (9, 6)  # 3x3 * 3-vector
CROSS_COLUMNS = (18, 9)  # [p]x M: 9 entries of y*c2 - z*c1
SYM_SANDWICH = (27 + 18, 18 + 12)  # R*A, then 6 dot products (lower triangle)

PIECES = {
    # se3::exp(S*theta): scale S by theta (6 mul); norm: 3 mul 2 add + sqrt;
    # ExpCoefficients: t2 (1 mul), a = s/t, b = (1-c)/t2 (1 sub), c = (t-s)/(t2*t)
    # (1 sub, 1 mul) -> 3 div + sin_cos; i_plus_aw_bw2 for R and for J: the 6 products
    # w_i w_j once, per call 3 diagonal entries (1 add, 1 mul, 1 sub) and 6 off-diagonal
    # entries from 6 distinct products (b*xy, b*xz, b*yz, a*x, a*y, a*z) and 1 add each;
    # translation J*v.
    "exp": {
        "mul": 6 + 3 + 2 + 6 + 2 * (3 + 6) + MAT3_VEC[0],
        "add": 2 + 2 + 2 * (6 + 6) + MAT3_VEC[1],
        "div": 3,
        "sqrt": 1,
        "sin_cos": 1,
    },
    # Transform * Transform: R1 R2, R1 p2 + p1.
    "compose": {
        "mul": MAT3_MUL[0] + MAT3_VEC[0],
        "add": MAT3_MUL[1] + MAT3_VEC[1] + 3,
    },
    # transport_covariance: A' = R A R^T and D' = R D R^T (sym_sandwich), B' = R B R^T
    # (two full products), P A', P B', P (P A')^T (cross_columns, all 9 entries as
    # written), E = P A' + B'^T (9 add), lower-right 6 entries x 3 add.
    "transport": {
        "mul": 2 * SYM_SANDWICH[0] + 2 * MAT3_MUL[0] + 3 * CROSS_COLUMNS[0],
        "add": 2 * SYM_SANDWICH[1] + 2 * MAT3_MUL[1] + 3 * CROSS_COLUMNS[1] + 9 + 18,
    },
    # c += transported: a full 6x6 add.
    "accumulate": {"mul": 0, "add": 36},
    # Transform::inverse: R^T p (negation free).
    "inverse": {"mul": MAT3_VEC[0], "add": MAT3_VEC[1]},
}


def add(*ds):
    out = {}
    for d in ds:
        for k, v in d.items():
            out[k] = out.get(k, 0) + v
    return out


def count(n):
    p = PIECES
    per_joint = add(p["exp"], p["compose"], p["transport"], p["accumulate"])
    # After the loop: pose = P * M, then pose.inverse().transport_covariance(c).
    tail = add(p["compose"], p["inverse"], p["transport"])
    total = add(*([per_joint] * n), tail)
    return per_joint, tail, total


def main():
    args = sys.argv[1:]
    n = 6
    ghz = None
    fma_per_cycle = 2
    i = 0
    while i < len(args):
        if args[i] == "--ghz":
            ghz = float(args[i + 1])
            i += 2
        elif args[i] == "--fma-per-cycle":
            fma_per_cycle = int(args[i + 1])
            i += 2
        else:
            n = int(args[i])
            i += 1
    per_joint, tail, total = count(n)
    flops = total["mul"] + total["add"]
    # With every add fused into a multiply (FMA), the multiplies alone need
    # mul / fma_per_cycle cycles on the FMA pipes; more adds than multiplies would need
    # add / fma_per_cycle. So the mul/add arithmetic needs >= max(mul, add) / K cycles.
    cycles = max(total["mul"], total["add"]) / fma_per_cycle
    out = {
        "n": n,
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
