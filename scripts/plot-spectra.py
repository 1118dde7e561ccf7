# The decaying-turbulence spectra of docs/numerics.md as a picture: python3 scripts/plot-spectra.py SPECTRA.csv [OUT.png]
# (the CSV from FORESTWIND_SPECTRA_CSV=SPECTRA.csv build/validation_tests "validation: decaying*").
import csv, collections
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import sys
rows = list(csv.DictReader(open(sys.argv[1] if len(sys.argv) > 1 else "spectra.csv")))
series = collections.OrderedDict()
start = None
for r in rows:
    key = f"{r['scheme']}, C_s {r['smagorinsky']}"
    series.setdefault(key, []).append((float(r['m']), float(r['E_end'])))
    if start is None or key == list(series)[0]:
        pass
first = list(series)[0]
start = [(float(r['m']), float(r['E_start'])) for r in rows if f"{r['scheme']}, C_s {r['smagorinsky']}" == first]
fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
ax.loglog([m for m, _ in start], [e for _, e in start], "k:", label="start (von Karman box)")
for key, pts in series.items():
    ax.loglog([m for m, _ in pts], [e for _, e in pts], "-o", ms=3, label=key + ", after 8 s")
ref = [(m, e) for m, e in series[list(series)[2]] if 2 <= m <= 4]
anchor = sum(e * m ** (5 / 3) for m, e in ref) / len(ref)
ms = [1, 32]
ax.loglog(ms, [anchor * m ** (-5 / 3) for m in ms], "k--", lw=1, label="-5/3")
ax.axvline(8, color="grey", lw=0.8)
ax.text(8.3, 2e-4, "8 cells", color="grey")
ax.set_xlabel("shell m (wavelength 64 / m cells)")
ax.set_ylabel("E(m), m$^2$/s$^2$")
ax.set_title("Decaying turbulence, 64$^3$ periodic box, 5 m/s mean wind, one turnover")
ax.set_ylim(1e-5, 1)
ax.legend(fontsize=7)
fig.tight_layout()
fig.savefig(sys.argv[2] if len(sys.argv) > 2 else "docs/spectra-decaying.png")
