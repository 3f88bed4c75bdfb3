"""The rest window at the paper's size: the paper-size sweep under the default rest test (0.1
within 0.05 time units) against the same sweep under 0.01 and under 0.005, droplet by droplet, and
two checks of what the default window itself loses.

Reads ../paper_size/paper.db (the default study) and rest_window_paper_W.db (the same sweep with
--rest-window W), all made by rest_window_paper.sh. Writes:

- rest_window_paper.csv: per short window and porosity, the droplets that passed under each
  window, those that passed under 0.05 and were stopped under the short one, the T of the passed
  droplets, and the steps;
- rest_window_paper_lost.csv: each droplet lost under 0.005, run again alone from its start under
  windows from 0.05 down to 0.005 (its outcome and steps under each);
- rest_window_paper_no_rest.csv: the first media of every porosity, and the two media where
  droplets paused longest before passing, run again with no rest test: each droplet's outcome,
  T and steps beside the stored ones.

Needs the Python module (PYTHONPATH=build/python).
"""
import multiprocessing as mp
import sqlite3
import sys

import pandas as pd
import softdrop

DEFAULT, SHORT = "../paper_size/paper.db", [0.01, 0.005]  # the shortest last: its lost droplets are run again
WINDOWS = [0.05, 0.03, 0.02, 0.01, 0.0075, 0.005]
NO_REST_MEDIA_PER_POROSITY = 6
KEY = ["porosity_index", "medium_index", "droplet"]


def read(db, query):
    with sqlite3.connect(f"file:{db}?mode=ro", uri=True) as c:
        return pd.read_sql(query, c)


def droplets(db):
    return read(db, "SELECT d.porosity_index, d.medium_index, d.droplet, m.target_porosity, m.medium_seed, "
                    "d.start_x, d.outcome, d.tortuosity, d.steps FROM sweep_droplets d "
                    "JOIN sweep_media m USING (sweep_id, porosity_index, medium_index) WHERE d.sweep_id = 1")


_media = {}


def rerun(row, window):
    """The droplet alone from its stored start, under a rest window (0: no rest test)."""
    key = (row["target_porosity"], row["medium_seed"])
    if key not in _media:  # the sweep's medium: its target porosity and seed (stored signed)
        _media[key] = softdrop.Medium.generate(porosity=row["target_porosity"], seed=int(row["medium_seed"]) % 2**64)
    return softdrop.simulate(_media[key], x0=row["start_x"], run=softdrop.RunOptions(rest_window=window))


def under_windows(row):
    out = {}
    for w in WINDOWS:
        r = rerun(row, w)
        out[f"outcome_{w}"], out[f"steps_{w}"] = r.outcome, r.steps
        if w == 0.05:
            out["same_as_stored"] = r.outcome == "passed" and r.tortuosity == row["tortuosity"]
    return out


def without_rest_test(row):
    r = rerun(row, 0)
    return {"outcome_no_rest": r.outcome, "tortuosity_no_rest": r.tortuosity if r.outcome == "passed" else None,
            "steps_no_rest": r.steps}


def main():
    default, rows = droplets(DEFAULT), []
    for window in SHORT:
        d = default.merge(droplets(f"rest_window_paper_{window}.db")[KEY + ["outcome", "tortuosity", "steps"]],
                          on=KEY, suffixes=("", "_short"))
        assert len(d) == 400_000, len(d)
        passed, passed_short = d.outcome == "passed", d.outcome_short == "passed"
        d["lost"] = passed & ~passed_short
        for (i, phi), g in d.groupby(["porosity_index", "target_porosity"]):
            p, ps = g.outcome == "passed", g.outcome_short == "passed"
            rows.append({"rest_window": window, "target_porosity": phi, "droplets": len(g), "passed": int(p.sum()),
                         "passed_short": int(ps.sum()), "lost": int(g.lost.sum()), "gained": int((~p & ps).sum()),
                         "tortuosity_changed": int((g.tortuosity[p & ps] != g.tortuosity_short[p & ps]).sum()),
                         "mean_t": g.tortuosity[p].mean(), "mean_t_short": g.tortuosity_short[ps].mean(),
                         "mean_t_of_lost": g.tortuosity[g.lost].mean(),
                         "steps_ratio": g.steps_short.sum() / g.steps.sum(),
                         "stuck_steps_share": g.steps[~p].sum() / g.steps.sum()})
        print(f"rest window {window}:", int(d.lost.sum()), "lost,", round(d.steps_short.sum() / d.steps.sum(), 4),
              "of the steps; passed droplets' share of the steps", round(d.steps[passed].sum() / d.steps.sum(), 4))
    table = pd.DataFrame(rows)
    table.to_csv("rest_window_paper.csv", index=False)
    print(table.to_string(index=False))

    with mp.Pool(2) as pool:
        # to_dict("records"), not iterrows: iterrows makes a row's 64-bit seed a float
        lost = d[d.lost].reset_index(drop=True)
        lost = pd.concat([lost, pd.DataFrame(pool.map(under_windows, lost.to_dict("records"), chunksize=4))], axis=1)
        lost.drop(columns=["lost"]).to_csv("rest_window_paper_lost.csv", index=False)
        print("lost under 0.005, run again: the same T under 0.05:", int(lost.same_as_stored.sum()), "of", len(lost))
        for w in WINDOWS:
            print(f"  stopped under {w}: {int((lost[f'outcome_{w}'] != 'passed').sum())}")
        # The media where droplets paused 0.02 time units or longer and then passed, and the first media
        # of every porosity.
        paused = lost[lost["outcome_0.02"] != "passed"][["porosity_index", "medium_index"]].drop_duplicates()
        first = d[d.medium_index < NO_REST_MEDIA_PER_POROSITY][["porosity_index", "medium_index"]].drop_duplicates()
        media = pd.concat([first, paused]).drop_duplicates()
        sample = d.merge(media).reset_index(drop=True)
        sample = pd.concat([sample, pd.DataFrame(pool.map(without_rest_test, sample.to_dict("records"), chunksize=4))],
                           axis=1)
    cols = KEY + ["target_porosity", "start_x", "outcome", "tortuosity", "steps", "outcome_no_rest",
                  "tortuosity_no_rest", "steps_no_rest"]
    sample[cols].to_csv("rest_window_paper_no_rest.csv", index=False)
    both = (sample.outcome == "passed") & (sample.outcome_no_rest == "passed")
    print("no rest test:", len(sample), "droplets in", len(media), "media;",
          int(((sample.outcome != "passed") & (sample.outcome_no_rest == "passed")).sum()), "pass only without it,",
          int(((sample.outcome == "passed") & (sample.outcome_no_rest != "passed")).sum()), "only with it;",
          int((sample.tortuosity[both] != sample.tortuosity_no_rest[both]).sum()), "T changed;",
          round(sample.steps_no_rest.sum() / sample.steps.sum(), 3), "times the steps")


if __name__ == "__main__":
    sys.exit(main())
