"""How wide a text is drawn, so that boxes can be made to fit their text.

The renders name DejaVu Sans (SFC) and DejaVu Sans Mono (LD, FBD, listings) first; their
advance widths (thousandths of an em, measured once from the fonts' files for the printable
ASCII characters) make a width that is exact where the font is installed and an upper bound
where a browser falls back to Arial or Consolas, which are narrower. Other characters count
as one em.

>>> round(text_width("DRAIN_VALVE", 12), 1), round(text_width("DRAIN_VALVE", 12, "mono"), 1)
(83.2, 79.5)
"""

from __future__ import annotations

_SANS = (
    "318 401 460 838 636 950 780 275 390 390 500 838 318 361 318 337 636 636 636 636 636 636 "
    "636 636 636 636 337 337 838 838 838 531 1000 684 686 698 770 632 575 775 752 295 295 656 "
    "557 863 748 787 603 787 695 635 611 732 684 989 685 611 685 390 337 390 838 500 500 613 "
    "635 550 635 615 352 635 634 278 278 579 278 974 634 612 635 635 411 521 392 634 592 818 "
    "592 592 525 636 337 636 838")
_SANS_BOLD = (
    "348 456 521 838 696 1002 872 306 457 457 523 838 380 415 380 365 696 696 696 696 696 696 "
    "696 696 696 696 400 400 838 838 838 580 1000 774 762 734 830 683 683 821 837 372 372 775 "
    "637 995 837 850 733 850 770 720 682 812 774 1103 771 724 725 457 365 457 838 500 500 675 "
    "716 593 716 678 435 716 712 343 343 665 343 1042 712 687 716 716 493 595 478 712 652 924 "
    "645 652 582 712 365 712 838")
_TABLES = {"sans": [int(w) for w in _SANS.split()],
           "sans-bold": [int(w) for w in _SANS_BOLD.split()]}
MONO_EM = 0.602  # DejaVu Sans Mono: every character 1233/2048 em


def text_width(s: str, size: float, font: str = "sans") -> float:
    """The width in px of ``s`` at ``size`` px in ``font`` ("sans", "sans-bold", "mono")."""
    if font == "mono":
        return len(s) * MONO_EM * size
    table = _TABLES[font]
    em = sum(table[ord(c) - 32] if 32 <= ord(c) < 127 else 1000 for c in s)
    return em * size / 1000


__all__ = ["MONO_EM", "text_width"]
