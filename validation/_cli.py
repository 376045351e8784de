"""What the validation scripts' command lines share."""
from __future__ import annotations

import argparse


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {value}")
    return value


def add_workers_option(ap: argparse.ArgumentParser, default: int | None = None,
                       why: str = "default: all cores; 1: in this process") -> None:
    """``--workers N``: the study runner's local worker processes, checked when parsed."""
    ap.add_argument("--workers", type=_positive_int, metavar="N", default=default,
                    help=f"local worker processes of the study runner ({why})")
