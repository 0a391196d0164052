#!/usr/bin/env python3
"""profile.py - where the instructions go on the Cortex-M0 (tools/mcu/profile.sh).

Reads the per-address execution counts written by qemu_pc_count.c and the ELF
(through arm-none-eabi-nm and -objdump) and prints:
  - a flat profile: instructions executed inside each function (self);
  - calls per call site for the run-time helpers (64-bit multiply/divide, ...)
    and other hot callees;
  - the instruction mix and an estimate of cycles per instruction for a
    Cortex-M0 and a Cortex-M0+ with zero-wait-state memory (ARM's TRM cycle
    counts; conditional branches counted taken when the next address ran
    fewer times, i.e. a lower bound on taken branches, and all taken as the
    upper bound).

Usage: profile.py ELF PC_COUNTS [TOP]
"""
import bisect
import re
import subprocess
import sys


def run(*cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def main():
    elf, counts_path = sys.argv[1], sys.argv[2]
    top = int(sys.argv[3]) if len(sys.argv) > 3 else 25
    counts = {}
    with open(counts_path) as f:
        for line in f:
            pc, c = line.split()
            counts[int(pc, 16)] = int(c)
    total = sum(counts.values())

    # Functions by address; aliases (__aeabi_lmul = __muldi3) share a name;
    # assembler functions without a size extend to the next symbol.
    by_addr = {}
    for line in run("arm-none-eabi-nm", "-n", "-S", "--defined-only", elf).splitlines():
        p = line.split()
        if len(p) in (3, 4) and p[-2] in "tT" and not p[-1].startswith("$"):
            a = int(p[0], 16) & ~1
            size = int(p[1], 16) if len(p) == 4 else 0
            old = by_addr.get(a, (0, []))
            by_addr[a] = (max(old[0], size), old[1] + [p[-1]])
    starts = sorted(by_addr)
    syms = []
    for i, a in enumerate(starts):
        size, names = by_addr[a]
        if size == 0 and i + 1 < len(starts):
            size = starts[i + 1] - a
        syms.append((a, size, "/".join(names)))
    alias = {n: s[2] for s in syms for n in s[2].split("/")}

    def func(pc):
        i = bisect.bisect_right(starts, pc) - 1
        if i >= 0 and pc < syms[i][0] + max(syms[i][1], 2):
            return syms[i][2]
        return "?"

    insns = []
    pat = re.compile(r"\s*([0-9a-f]+):\s+[0-9a-f]{4}(?: [0-9a-f]{4})?\s+(\S+)\s*(.*)")
    for line in run("arm-none-eabi-objdump", "-d", elf).splitlines():
        m = pat.match(line)
        if m:
            insns.append((int(m.group(1), 16), m.group(2), m.group(3)))

    self_cost, calls = {}, {}
    for pc, c in counts.items():
        fn = func(pc)
        self_cost[fn] = self_cost.get(fn, 0) + c
    for pc, op, ops in insns:
        c = counts.get(pc, 0)
        m = re.search(r"<([^>+]+)>", ops)
        if c and op == "bl" and m:
            callee = alias.get(m.group(1), m.group(1))
            calls.setdefault(callee, {})
            caller = func(pc)
            calls[callee][caller] = calls[callee].get(caller, 0) + c

    print(f"instructions executed: {total}")
    helpers = sum(v for k, v in self_cost.items() if k.startswith("__"))
    print(f"  in compiler run-time helpers (__*, libgcc: 64-bit multiply/divide, ...): "
          f"{helpers} = {100 * helpers / total:.1f} %")
    print(f"\nflat profile (self), top {top}:")
    print(f"  {'instructions':>12} {'share':>6} {'calls':>9} {'per call':>9}  function")
    for fn, c in sorted(self_cost.items(), key=lambda x: -x[1])[:top]:
        n = sum(calls.get(fn, {}).values())
        per = f"{c / n:9.1f}" if n else f"{'':9}"
        print(f"  {c:12d} {100 * c / total:5.1f}% {n:9d} {per}  {fn}")

    print("\ncallers of the hottest callees (calls):")
    hot = [fn for fn, _ in sorted(self_cost.items(), key=lambda x: -x[1])[:12] if fn in calls]
    for fn in hot:
        by = sorted(calls[fn].items(), key=lambda x: -x[1])
        print(f"  {fn}: " + ", ".join(f"{k} {v}" for k, v in by[:8]))

    def nregs(ops):
        m = re.search(r"\{([^}]*)\}", ops)
        n = 0
        for part in (m.group(1).split(",") if m else []):
            part = part.strip()
            if "-" in part:
                a, b = part.split("-")
                n += int(b[1:]) - int(a[1:]) + 1
            else:
                n += 1
        return n

    cond = re.compile(r"b(eq|ne|cs|hs|cc|lo|mi|pl|vs|vc|hi|ls|ge|lt|gt|le)$")
    mix = {}
    cyc = {"M0": [0, 0], "M0+": [0, 0]}  # [likely, all branches taken]

    def add(kind, c, m0, m0p, m0_taken=None, m0p_taken=None, taken=0):
        mix[kind] = mix.get(kind, 0) + c
        if m0_taken is None:
            for k, v in (("M0", m0), ("M0+", m0p)):
                cyc[k][0] += v * c
                cyc[k][1] += v * c
        else:
            for k, v, t in (("M0", m0, m0_taken), ("M0+", m0p, m0p_taken)):
                cyc[k][0] += v * c + (t - v) * taken
                cyc[k][1] += t * c

    for pc, op, ops in insns:
        c = counts.get(pc, 0)
        if not c:
            continue
        base = op.split(".")[0]
        if base in ("ldr", "ldrb", "ldrh", "ldrsb", "ldrsh", "str", "strb", "strh"):
            add("load/store", c, 2, 2)
        elif base == "pop" and "pc" in ops:
            n = nregs(ops) - 1
            add("pop {..pc}", c, 4 + n, 3 + n)
        elif base in ("push", "pop", "ldm", "ldmia", "stm", "stmia"):
            n = nregs(ops)
            add("push/pop/ldm/stm", c, 1 + n, 1 + n)
        elif base == "bl":
            add("bl", c, 4, 3)
        elif base in ("bx", "blx"):
            add("bx/blx", c, 3, 2)
        elif base == "b":
            add("b", c, 3, 2)
        elif cond.match(base):
            taken = max(0, c - counts.get(pc + 2, 0))
            add("b<cond>", c, 1, 1, 3, 2, taken)
        elif base in ("mul", "muls"):
            add("muls", c, 1, 1)
        elif base in ("mov", "add") and ops.startswith("pc"):
            add("write pc", c, 3, 2)
        else:
            add("alu", c, 1, 1)
    counted = sum(mix.values())
    print("\ninstruction mix:")
    for k, v in sorted(mix.items(), key=lambda x: -x[1]):
        print(f"  {k:18s} {v:12d} {100 * v / counted:5.1f}%")
    print("cycles per instruction, zero wait states, single-cycle multiplier (estimate):")
    for k, (likely, hi) in cyc.items():
        print(f"  Cortex-{k}: {likely / counted:.2f} (branches as measured) .. "
              f"{hi / counted:.2f} (every conditional branch taken)")


if __name__ == "__main__":
    main()
