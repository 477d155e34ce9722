"""Account names are unique as people read them: compared after Unicode NFKC (a
full-width "A", U+FF21, is "A") and casefolding ("ANA" is "ana")."""

from __future__ import annotations

import unicodedata


def name_key(name: str) -> str:
    """The form two account names are compared in (Unicode's NFKC_Casefold, near enough):
    NFKC, casefolded, NFKC again (casefolding can undo the normal form)."""
    folded = unicodedata.normalize("NFKC", name.strip()).casefold()
    return unicodedata.normalize("NFKC", folded)
