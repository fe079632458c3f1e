"""``cusp verify``: derive the paper's closed forms with sympy and check them.

For every equation: the printed form (as read from the paper, ``docs/verification.md``), the
form sympy derived from the defining integrals, whether they agree (and how that was decided:
``symbolic`` or ``numeric, N points at D digits``), and whether the float implementation in
``models`` agrees with the derived expression evaluated by mpmath at high precision.

Exit status: 0 when every printed form meets its expectation (paper readings agree with the
derivation, alternative readings of garbled text disagree) and every implementation
comparison agrees; 1 otherwise (in particular whenever a derivation disagrees with the
implementation, or the implementation cannot be imported).
"""

from __future__ import annotations

import argparse
import json
import sys
import textwrap
import time

#: equations whose derived expression has a counterpart in the float models
COMPARED = ("9", "12 (slip)", "12", "15", "21", "22", "28", "29", "30", "31", "MD", "AB", "32")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--json",
        action="store_true",
        help="print a JSON list of records (equation, printed, derived, agrees, "
        "implementation_agrees, method, detail, ...) instead of the table",
    )


def records(models=None) -> list[dict]:
    """Derive, verify and compare; one JSON-ready dict per equation."""
    import cusp.verification as verification

    impl = verification.check_implementation(models)
    unavailable = impl.get("*")
    out = []
    for der in verification.derive_all():
        verdict = verification.check_printed(der)
        rec = {
            "equation": der.equation,
            "title": der.title,
            "role": der.role,
            "printed": str(der.printed),
            "derived": str(der.derived),
            "agrees": verdict.agrees,
            "expected_agreement": der.expected_agreement,
            "method": verdict.method,
            "detail": verdict.detail,
            "steps": " ".join(der.steps),
        }
        if der.role != "paper" or der.equation not in COMPARED:
            rec.update(
                implementation=None,
                implementation_max_rel_error=None,
                implementation_error_over_tolerance=None,
                implementation_compared=False,
                implementation_agrees=True,
                implementation_detail="no counterpart in models/ (not compared)",
            )
        elif unavailable:
            rec.update(
                implementation=None,
                implementation_max_rel_error=None,
                implementation_error_over_tolerance=None,
                implementation_compared=False,
                implementation_agrees=False,
                implementation_detail=unavailable[0].detail,
            )
        else:
            checks = impl.get(der.equation, [])
            rec.update(
                implementation=", ".join(str(chk.implementation) for chk in checks),
                implementation_max_rel_error=max((c.max_rel_error for c in checks), default=None),
                implementation_error_over_tolerance=max(
                    (c.max_error_over_tolerance for c in checks), default=None
                ),
                implementation_compared=bool(checks),
                implementation_agrees=bool(checks) and all(chk.agrees for chk in checks),
                implementation_detail=" | ".join(
                    f"{chk.implementation}: {chk.detail}" for chk in checks
                )
                or "comparison missing",
            )
        out.append(rec)
    return out


def exit_status(recs: list[dict]) -> int:
    bad = [
        r for r in recs if r["agrees"] != r["expected_agreement"] or not r["implementation_agrees"]
    ]
    return 1 if bad else 0


def _cell(text: str, width: int) -> list[str]:
    return textwrap.wrap(text, width, break_long_words=True, break_on_hyphens=False) or [""]


def _reading_notes(recs: list[dict]) -> list[str]:
    """One line per garbled equation: which reading the derivation supports."""
    notes = []
    for base in sorted({r["equation"].split(" (reading")[0] for r in recs if r["role"] != "paper"}):
        paper = [r for r in recs if r["equation"] == base]
        alts = [r for r in recs if r["equation"].startswith(f"{base} (reading")]
        ok = [r["equation"] for r in alts if r["agrees"]]
        wrong = [r["equation"] for r in alts if not r["agrees"]]
        verdict = "agrees" if paper and paper[0]["agrees"] else "DISAGREES"
        notes.append(
            f"Eq {base}, garbled in the extracted text: the adopted reading "
            f"[{paper[0]['printed'] if paper else '?'}] {verdict} with the "
            f"derivation; alternative readings agreeing: {', '.join(ok) or 'none'}; "
            f"disagreeing: {', '.join(wrong) or 'none'} (see docs/verification.md)."
        )
    return notes


def format_table(recs: list[dict]) -> str:
    cols = (
        ("equation", 15),
        ("printed", 38),
        ("derived", 38),
        ("verdict", 22),
        ("implementation", 26),
    )
    lines = [
        "  ".join(name.ljust(wd) for name, wd in cols).rstrip(),
        "  ".join("-" * wd for _, wd in cols),
    ]
    for r in recs:
        verdict = "agrees" if r["agrees"] else "DISAGREES"
        if r["role"] != "paper":
            verdict += " (expected)" if r["agrees"] == r["expected_agreement"] else " (UNEXPECTED)"
        verdict += f" [{r['method']}]"
        if not r["implementation_compared"]:
            impl = "n/a" if r["implementation_agrees"] else "NOT RUN: models unavailable"
        else:
            impl = "agrees" if r["implementation_agrees"] else "DISAGREES"
            err = r.get("implementation_max_rel_error")
            ratio = r.get("implementation_error_over_tolerance")
            if err is not None:
                impl += f", max rel. error {err:.1e} ({ratio:.1g} of tolerance)"
        cells = [
            _cell(r["equation"], cols[0][1]),
            _cell(r["printed"], cols[1][1]),
            _cell(r["derived"], cols[2][1]),
            _cell(verdict, cols[3][1]),
            _cell(impl, cols[4][1]),
        ]
        for i in range(max(len(cell) for cell in cells)):
            row = [
                (cell[i] if i < len(cell) else "").ljust(wd)
                for cell, (_, wd) in zip(cells, cols, strict=True)
            ]
            lines.append("  ".join(row).rstrip())
        lines.append("")
    lines += _reading_notes(recs)
    problems = [r for r in recs if not r["implementation_agrees"]]
    for r in problems:
        lines.append(f"implementation, Eq {r['equation']}: {r['implementation_detail']}")
    return "\n".join(lines)


def main(args: argparse.Namespace) -> int:
    start = time.perf_counter()
    recs = records()
    status = exit_status(recs)
    if args.json:
        json.dump(recs, sys.stdout, indent=1)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(format_table(recs) + "\n")
        n_bad = sum(r["agrees"] != r["expected_agreement"] for r in recs)
        n_impl = sum(not r["implementation_agrees"] for r in recs)
        sys.stdout.write(
            f"{len(recs)} equations; {n_bad} unexpected printed-form verdicts; "
            f"{n_impl} implementation comparisons failed or not run; "
            f"{time.perf_counter() - start:.1f} s\n"
        )
    return status
