#pragma once
// The softdrop database's schema as SQL, by version (internal to the store; sqlite_file.cpp
// creates and migrates it). README.md ("The database") documents it; keep the two in step.

namespace softdrop::detail {

// The schema as SQL, by version. Tables that share column shapes (run_id, generation, x, y) are
// alike because they describe the same rows' keys; each is written once, here.
// Version 1: the search history.
inline constexpr const char* kSchemaV1 = R"sql(
CREATE TABLE IF NOT EXISTS runs (
  id              INTEGER PRIMARY KEY,
  created         TEXT NOT NULL,
  updated         TEXT NOT NULL,
  version         TEXT NOT NULL,
  status          TEXT NOT NULL CHECK (status IN ('running', 'finished', 'interrupted')),
  params          TEXT NOT NULL,
  seed            INTEGER NOT NULL,
  lambda          INTEGER NOT NULL,
  grains          INTEGER NOT NULL,
  width           REAL NOT NULL,
  height          REAL NOT NULL,
  periodic        INTEGER NOT NULL,
  generations     INTEGER NOT NULL,
  evaluations     INTEGER NOT NULL,
  best_t          REAL NOT NULL,
  best_generation INTEGER NOT NULL,
  island          INTEGER,
  archipelago     INTEGER
);
CREATE TABLE IF NOT EXISTS generations (
  run_id             INTEGER NOT NULL REFERENCES runs(id) ON DELETE CASCADE,
  generation         INTEGER NOT NULL,
  kind               TEXT NOT NULL CHECK (kind IN ('initial', 'all', 'single', 'relocate', 'migrate', 'mixed')),
  accepted_candidate INTEGER,
  best_t             REAL NOT NULL,
  touched            INTEGER NOT NULL,
  seconds            REAL NOT NULL,
  finished           TEXT NOT NULL,
  PRIMARY KEY (run_id, generation)
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS candidates (
  run_id      INTEGER NOT NULL,
  generation  INTEGER NOT NULL,
  candidate   INTEGER NOT NULL,
  moved_grain INTEGER,
  moved       INTEGER NOT NULL,
  outcome     TEXT NOT NULL CHECK (outcome IN ('passed', 'stuck', 'timeout', 'diverged')),
  reason      TEXT NOT NULL,
  tortuosity  REAL,
  steps       INTEGER NOT NULL,
  touched     INTEGER NOT NULL,
  seconds     REAL NOT NULL,
  PRIMARY KEY (run_id, generation, candidate),
  FOREIGN KEY (run_id, generation) REFERENCES generations(run_id, generation) ON DELETE CASCADE
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS grains (
  run_id     INTEGER NOT NULL,
  generation INTEGER NOT NULL,
  grain      INTEGER NOT NULL,
  x          REAL NOT NULL,
  y          REAL NOT NULL,
  r          REAL NOT NULL,
  touched    INTEGER NOT NULL,
  PRIMARY KEY (run_id, generation, grain),
  FOREIGN KEY (run_id, generation) REFERENCES generations(run_id, generation) ON DELETE CASCADE
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS paths (
  run_id     INTEGER NOT NULL,
  generation INTEGER NOT NULL,
  point      INTEGER NOT NULL,
  x          REAL NOT NULL,
  y          REAL NOT NULL,
  PRIMARY KEY (run_id, generation, point),
  FOREIGN KEY (run_id, generation) REFERENCES generations(run_id, generation) ON DELETE CASCADE
) WITHOUT ROWID;
)sql";

// Version 2 adds the porosity sweeps.
inline constexpr const char* kSchemaV2 = R"sql(
CREATE TABLE IF NOT EXISTS sweeps (
  id          INTEGER PRIMARY KEY,
  created     TEXT NOT NULL,
  updated     TEXT NOT NULL,
  version     TEXT NOT NULL,
  status      TEXT NOT NULL CHECK (status IN ('running', 'complete', 'interrupted')),
  params      TEXT NOT NULL UNIQUE,
  units       INTEGER NOT NULL
);
CREATE TABLE IF NOT EXISTS sweep_media (
  sweep_id        INTEGER NOT NULL REFERENCES sweeps(id) ON DELETE CASCADE,
  porosity_index  INTEGER NOT NULL,
  medium_index    INTEGER NOT NULL,
  target_porosity REAL NOT NULL,
  porosity        REAL NOT NULL,
  grains          INTEGER NOT NULL,
  medium_seed     INTEGER NOT NULL,
  droplets        INTEGER NOT NULL,
  passed          INTEGER NOT NULL,
  stuck           INTEGER NOT NULL,
  timeout         INTEGER NOT NULL,
  diverged        INTEGER NOT NULL,
  mean_t          REAL,
  standard_error  REAL,
  stuck_fraction  REAL NOT NULL,
  seconds         REAL NOT NULL,
  PRIMARY KEY (sweep_id, porosity_index, medium_index)
) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS sweep_droplets (
  sweep_id       INTEGER NOT NULL,
  porosity_index INTEGER NOT NULL,
  medium_index   INTEGER NOT NULL,
  droplet        INTEGER NOT NULL,
  start_x        REAL NOT NULL,
  outcome        TEXT NOT NULL CHECK (outcome IN ('passed', 'stuck', 'timeout', 'diverged')),
  tortuosity     REAL,
  steps          INTEGER NOT NULL,
  PRIMARY KEY (sweep_id, porosity_index, medium_index, droplet),
  FOREIGN KEY (sweep_id, porosity_index, medium_index)
    REFERENCES sweep_media(sweep_id, porosity_index, medium_index) ON DELETE CASCADE
) WITHOUT ROWID;
)sql";

// Version 3 stores a search strategy's state with each generation (NULL: none, as before).
inline constexpr const char* kSchemaV3 = "ALTER TABLE generations ADD COLUMN state TEXT";

// Version 6: the held-out values of runs' arrangements (softdrop validate, and the end of a search).
inline constexpr const char* kSchemaV6 = R"sql(
CREATE TABLE IF NOT EXISTS validations (
  run_id                 INTEGER NOT NULL REFERENCES runs(id),
  generation             INTEGER NOT NULL,
  seed                   INTEGER NOT NULL,
  starts                 INTEGER NOT NULL CHECK (starts >= 1),
  created                TEXT NOT NULL,
  version                TEXT NOT NULL,
  dt                     REAL NOT NULL,
  passed                 INTEGER NOT NULL,
  mean_t                 REAL,
  standard_error         REAL,
  q1                     REAL,
  median                 REAL,
  q3                     REAL,
  half_dt                INTEGER NOT NULL,
  half_dt_passed         INTEGER,
  half_dt_mean_t         REAL,
  half_dt_standard_error REAL,
  paired                 INTEGER,
  dt_shift               REAL,
  dt_shift_error         REAL,
  PRIMARY KEY (run_id, generation, seed, starts)
);
)sql";

// Version 7: the robust objectives. A run's droplet runs (NULL before: one per evaluation); a
// generation's re-run of the arrangement its candidates were made from (NULL: none, the single
// objective); a candidate's droplets and how many passed (NULL before: one).
struct AddedColumn {
  const char* table;
  const char* column;
  const char* type;
};
inline constexpr AddedColumn kSchemaV7[] = {{"runs", "droplets", "INTEGER"},
                                            {"generations", "parent_t", "REAL"},
                                            {"generations", "parent_passed", "INTEGER"},
                                            {"candidates", "droplets", "INTEGER"},
                                            {"candidates", "passed", "INTEGER"}};

// Version 8: each candidate's move (NULL before: the generation's kind tells it, except for es,
// which drew each candidate's own), a generation kind 'mixed' for those, and the views below.
inline constexpr AddedColumn kSchemaV8[] = {{"candidates", "kind", "TEXT"}};

// Version 9: each sweep droplet's shaken_at and route_tortuosity (NULL before: not recorded), and
// the views again.
inline constexpr AddedColumn kSchemaV9[] = {{"sweep_droplets", "shaken_at", "REAL"},
                                            {"sweep_droplets", "route_tortuosity", "REAL"}};

// Version 10: the second droplets of sweeps that push two droplets one after the other (one row
// a pair whose second was released; the pair's first is its sweep_droplets row). Its first ten
// columns are sweep_droplets' on purpose: a second droplet is a droplet, read by the same code.
inline constexpr const char* kSchemaV10 = R"sql(
CREATE TABLE IF NOT EXISTS sweep_second_droplets (
  sweep_id         INTEGER NOT NULL,
  porosity_index   INTEGER NOT NULL,
  medium_index     INTEGER NOT NULL,
  droplet          INTEGER NOT NULL,
  start_x          REAL NOT NULL,
  outcome          TEXT NOT NULL CHECK (outcome IN ('passed', 'stuck', 'timeout', 'diverged')),
  tortuosity       REAL,
  steps            INTEGER NOT NULL,
  shaken_at        REAL,
  route_tortuosity REAL,
  released_at      REAL NOT NULL,
  first_held_at    REAL,
  held_at          REAL,
  contact_steps    INTEGER NOT NULL,
  shared_touched   INTEGER NOT NULL,
  PRIMARY KEY (sweep_id, porosity_index, medium_index, droplet),
  FOREIGN KEY (sweep_id, porosity_index, medium_index)
    REFERENCES sweep_media(sweep_id, porosity_index, medium_index) ON DELETE CASCADE
) WITHOUT ROWID;
)sql";

// The views: each table under the names the program's CSV and JSON and the Python frames use
// (`softdrop columns` lists them), for queries in SQL. Dropped and made again at each migration
// that changes them; a view holds no data.
inline constexpr const char* kViews = R"sql(
DROP VIEW IF EXISTS runs_view;
CREATE VIEW runs_view AS SELECT
  id AS run, created, updated, version, status,
  coalesce(json_extract(params, '$.strategy'), 'paper') AS strategy,
  coalesce(json_extract(params, '$.objective'), 'single') AS objective,
  seed, lambda, grains, width, height, periodic, generations, evaluations, droplets,
  best_t AS best_tortuosity, best_generation, island, archipelago, params
FROM runs;
DROP VIEW IF EXISTS generations_view;
CREATE VIEW generations_view AS SELECT
  run_id AS run, generation, kind, accepted_candidate, best_t AS best_tortuosity, touched, seconds,
  finished, state, parent_t AS parent_tortuosity, parent_passed
FROM generations;
DROP VIEW IF EXISTS candidates_view;
CREATE VIEW candidates_view AS SELECT
  c.run_id AS run, c.generation, c.candidate,
  coalesce(c.kind, CASE WHEN g.kind NOT IN ('all', 'mixed') OR c.moved_grain IS NULL THEN g.kind END) AS kind,
  c.moved_grain, c.moved, c.outcome, c.reason, c.tortuosity, c.steps, c.touched, c.seconds,
  coalesce(c.droplets, 1) AS droplets, coalesce(c.passed, c.outcome = 'passed') AS passed
FROM candidates c JOIN generations g USING (run_id, generation);
DROP VIEW IF EXISTS grains_view;
CREATE VIEW grains_view AS SELECT run_id AS run, generation, grain, x, y, r, touched FROM grains;
DROP VIEW IF EXISTS paths_view;
CREATE VIEW paths_view AS SELECT run_id AS run, generation, point, x, y FROM paths;
DROP VIEW IF EXISTS validations_view;
CREATE VIEW validations_view AS SELECT
  run_id AS run, generation, seed, starts, created, version, dt, passed, mean_t AS mean_tortuosity,
  standard_error, q1, median, q3, half_dt, half_dt_passed, half_dt_mean_t AS half_dt_mean_tortuosity,
  half_dt_standard_error, paired, dt_shift, dt_shift_error
FROM validations;
DROP VIEW IF EXISTS sweeps_view;
CREATE VIEW sweeps_view AS SELECT
  id AS sweep, created, updated, version, status, params, units,
  (SELECT count(*) FROM sweep_media m WHERE m.sweep_id = sweeps.id) AS done
FROM sweeps;
DROP VIEW IF EXISTS sweep_media_view;
CREATE VIEW sweep_media_view AS SELECT
  sweep_id AS sweep, porosity_index, medium_index, target_porosity, porosity, grains, medium_seed,
  droplets, passed, stuck, timeout, diverged, mean_t AS mean_tortuosity, standard_error, stuck_fraction,
  seconds
FROM sweep_media;
DROP VIEW IF EXISTS sweep_droplets_view;
CREATE VIEW sweep_droplets_view AS SELECT
  sweep_id AS sweep, porosity_index, medium_index, droplet, start_x, outcome, tortuosity, steps, shaken_at,
  route_tortuosity
FROM sweep_droplets;
DROP VIEW IF EXISTS sweep_second_droplets_view;
CREATE VIEW sweep_second_droplets_view AS SELECT
  sweep_id AS sweep, porosity_index, medium_index, droplet, start_x, outcome, tortuosity, steps, shaken_at,
  route_tortuosity, released_at, first_held_at, held_at, contact_steps, shared_touched
FROM sweep_second_droplets;
)sql";

}  // namespace softdrop::detail
