"""Report blocks: the film thickness by both methods side by side, and the model-error band
of this engine (formatting only; the numbers are the check's quantities)."""

from __future__ import annotations

import numpy as np

from ..api import CheckResult
from ..results.display import case_text
from .sections import fmt, in_unit, rpm


def film_method_blocks(res: CheckResult) -> list[dict]:
    """Short-bearing and finite-length MOFT at each bearing's worst judged point, their
    ratio, and the band over the engine, with the published comparisons behind it."""
    qs = res.outcome.quantities
    short, fin = qs.get("bearing.moft_short"), qs.get("bearing.moft_finite")
    if short is None or fin is None or short.values.shape != fin.values.shape:
        return []
    rows, ratios = [], []
    for i, n in enumerate(short.coords["item"]):
        for ci, c in enumerate(short.coords["case"]):
            s, f = short.values[i, ci], fin.values[i, ci]
            ok = np.isfinite(s) & np.isfinite(f) & (f > 0)
            if not ok.any():
                continue
            ks, kf = int(np.nanargmin(np.where(ok, s, np.inf))), int(
                np.nanargmin(np.where(ok, f, np.inf)))
            r = s[kf] / f[kf]
            ratios.append(r)
            def at(k: int) -> str:
                return f"{float(rpm(short.coords['speed'][k])):.0f}"

            rows.append([n, case_text(str(c)), fmt(in_unit(s[ks], "m", "um")), at(ks),
                         fmt(in_unit(f[kf], "m", "um")), at(kf), fmt(r)])
    if not rows:
        return []
    lo, hi = min(ratios), max(ratios)
    return [
        {"type": "heading", "text": "Short bearing and finite length side by side"},
        {"type": "table", "caption": "Thinnest film over the speeds by each method (short"
         " bearing: Booker's closed form; finite length: mobility map of the finite-length"
         " Reynolds equation with Swift-Stieber cavitation) and the ratio at the finite-length"
         " worst point",
         "columns": ["bearing", "case", "short [µm]", "at [rpm]", "finite [µm]", "at [rpm]",
                     "ratio"], "rows": rows, "detail": True, "sheet": "Film methods"},
        {"type": "text", "text":
         f"Model-error band on this engine: the short-bearing film is {lo:.2f} to {hi:.2f}"
         " times the finite-length film at the same point. The short-bearing approximation"
         " neglects the circumferential pressure flow and is optimistic at engine width ratios"
         " (Booker, J. Basic Eng. 87, 1965; finite-length impedances: Childs, Moes and van"
         " Leeuwen, J. Lubr. Technol. 99, 1977; Goenka, J. Tribology 106, 1984). Limits say"
         " which method they belong to: a full-film criterion (film over composite roughness)"
         " is judged on the finite-length film; a guideline calibrated to the short-bearing"
         " method on the short-bearing film. The finite-length map treats a partial groove by"
         " the effective width (measured on the example's mains with the groove as a"
         " zero-pressure strip: 25 % conservative at full load, 48 % optimistic at no load when"
         " the thinnest film lies under the groove)."},
    ]
