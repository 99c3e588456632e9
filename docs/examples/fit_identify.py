"""Worked example of docs/python.md: load a measured run, fit it, run identify, plot.

Run from the repository root after building (Debian's interpreter, which has numpy):
    PYTHONPATH=build/python MPLBACKEND=Agg /usr/bin/python3 docs/examples/fit_identify.py
Writes docs/img/python_fit_example.png.
"""
import io
import os
import pathlib

import matplotlib

matplotlib.use(os.environ.get("MPLBACKEND", "Agg"))
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import stickslip  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = pathlib.Path(os.environ.get("STICKSLIP_SHARED_DIR", ROOT.parent / "shared"))
DAMPER = SHARED / "data" / "real" / "friction-damper"


def load_run(path):
    """A measured run CSV ('#' lines skipped) as a dict of numpy arrays by column name."""
    with open(path) as f:
        text = "".join(line for line in f if not line.startswith("#"))
    table = np.genfromtxt(io.StringIO(text), delimiter=",", names=True)
    return {name: table[name] for name in table.dtype.names}


# 1. Load a measured run of the friction damper (prescribed displacement, 1 Hz, 30 lb band tension).
run = DAMPER / "1Hz_30lb_1in.csv"
held_out = DAMPER / "1Hz_36lb_1in.csv"
measured = load_run(run)
print(f"{run.name}: {len(measured['time_s'])} samples, {measured['time_s'][-1]:.2f} s, "
      f"columns {', '.join(measured)}")

# 2. Fit the rate-state and the Coulomb law to it; score both on a run at the other load.
report = stickslip.fit([run], validate_on=[held_out], model="both")
for row in report["comparison"]:
    print(f"  {row['role']:10s} {pathlib.Path(row['file']).name}: NRMSE Coulomb {row['nrmse_coulomb']:.4f}, "
          f"rate-state {row['nrmse_rate_state']:.4f}")
law = {name: p["value"] for name, p in report["parameters"].items()}
print("  rate-state parameters: " + ", ".join(f"{k} = {v:.4g}" for k, v in sorted(law.items())))
tN = report["preprocessing"]["runs"][0]["settings"]["tN"]["value"]
print(f"  t_N of the run (band tension): {tN:.2f} N")

# 3. Look for effects the model lacks, on the six 1 Hz runs (each held out in turn).
runs = sorted(DAMPER.glob("1Hz_*.csv"))
ident = stickslip.identify(runs, setup="prescribed")
print(f"identify on {len(runs)} runs: effects added: {[e['name'] for e in ident['effects_added']] or 'none'}")
print(f"  before: fit NRMSE {ident['before']['fit_nrmse']:.4f}, held-out {ident['before']['validation_nrmse']:.4f}")
print(f"  after:  fit NRMSE {ident['after']['fit_nrmse']:.4f}, held-out {ident['after']['validation_nrmse']:.4f}")
for c in ident["candidates"]:
    dbic = c["score"]["delta_bic"]
    verdict = "accepted" if c["accepted"] else (c.get("rejected_because") or "")[:60]
    print(f"  {c['name']:22s} dBIC {dbic if dbic is None else round(dbic, 1)!s:>7}  {verdict}")

# 4. Drive the fitted law along the measured displacement and plot it over the measurement.
sim = stickslip.simulate(input=run, f=1.0, tN=tN, **{k: law[k] for k in ("mu", "C1", "eta", "Dc", "vc", "epsT")})
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
ax1.plot(1e3 * measured["stage_disp_m"], 1e-3 * measured["friction_force_N"], lw=0.6, label="measured")
ax1.plot(1e3 * sim["stage_disp_m"], 1e-3 * sim["friction_force_N"], lw=0.8, label="fitted rate-state law")
ax1.set_xlabel("displacement [mm]")
ax1.set_ylabel("friction force [kN]")
ax1.set_title(f"{run.stem}: force-displacement loops")
ax1.legend(loc="upper left")
window = (measured["time_s"] >= 2.0) & (measured["time_s"] <= 4.0)
swin = (sim["time_s"] >= 2.0) & (sim["time_s"] <= 4.0)
ax2.plot(measured["time_s"][window], 1e-3 * measured["friction_force_N"][window], lw=0.8, label="measured")
ax2.plot(sim["time_s"][swin], 1e-3 * sim["friction_force_N"][swin], lw=0.9, label="fitted")
ax2.set_xlabel("time [s]")
ax2.set_ylabel("friction force [kN]")
ax2.set_title(f"fit NRMSE {report['fit_nrmse']:.3f}, held-out ({held_out.stem}) {report['validation_nrmse']:.3f}")
ax2.legend(loc="upper right")
fig.tight_layout()
out = ROOT / "docs" / "img" / "python_fit_example.png"
fig.savefig(out, dpi=100)
print(f"plot: {out.relative_to(ROOT)}")
