-- Droplet by droplet comparison of two sweeps with the same options but the constraint order:
-- main = the sequential reference (results/sweep/sweep.db), rb = red-black (attached). The two
-- sweeps share media and start positions (same seeds), so each droplet is paired with itself.
-- One row per porosity and one for all; ΔT = T(red-black) − T(sequential) over the droplets that
-- passed in both.
.mode csv
.headers on
ATTACH 'results/constraint_order/sweep.db' AS rb;
WITH pairs AS (
  SELECT a.porosity_index AS p, a.start_x = b.start_x AS same_start,
         a.outcome AS seq_outcome, b.outcome AS rb_outcome,
         CASE WHEN a.outcome = 'passed' AND b.outcome = 'passed' THEN b.tortuosity - a.tortuosity END AS dt,
         a.steps AS seq_steps, b.steps AS rb_steps
  FROM main.sweep_droplets a
  JOIN rb.sweep_droplets b USING (porosity_index, medium_index, droplet)
  WHERE a.sweep_id = 1 AND b.sweep_id = 1
),
groups AS (
  SELECT CAST(p AS TEXT) AS g, * FROM pairs
  UNION ALL
  SELECT 'all' AS g, * FROM pairs
)
SELECT
  CASE g WHEN 'all' THEN 'all' ELSE (SELECT printf('%.2f', target_porosity) FROM main.sweep_media m
                                     WHERE m.sweep_id = 1 AND m.porosity_index = CAST(g AS INTEGER) LIMIT 1) END
    AS target_porosity,
  COUNT(*) AS droplets,
  SUM(same_start) AS same_start,
  SUM(seq_outcome = rb_outcome) AS same_outcome,
  SUM(seq_outcome <> 'passed' AND rb_outcome = 'passed') AS passed_only_red_black,
  SUM(seq_outcome = 'passed' AND rb_outcome <> 'passed') AS passed_only_sequential,
  COUNT(dt) AS both_passed,
  printf('%.6f', AVG(dt)) AS mean_dt,
  printf('%.6f', sqrt((SUM(dt * dt) - COUNT(dt) * AVG(dt) * AVG(dt)) / (COUNT(dt) - 1))) AS sd_dt,
  printf('%.6f', sqrt((SUM(dt * dt) - COUNT(dt) * AVG(dt) * AVG(dt)) / (COUNT(dt) - 1) / COUNT(dt))) AS se_mean_dt,
  SUM(abs(dt) < 1e-3) AS within_1e3,
  SUM(seq_steps) AS seq_steps,
  SUM(rb_steps) AS rb_steps
FROM groups
GROUP BY g
ORDER BY g = 'all', CAST(g AS INTEGER);
