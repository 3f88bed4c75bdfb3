"""What calling softdrop from Python costs: a 200-droplet simulate_many against the program's
`simulate --droplets 200` on the same medium, seed and threads, run in turn (repeats alternate so
that both see the same machine). The program's time includes its start and the grain file's
reading; the module's includes building the DataFrame.

    PYTHONPATH=build/python python3 bench/python_overhead.py --cli build/softdrop \\
        --out bench/results/python-overhead.json
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import tempfile
import time

import softdrop


def timed(call):
    t0 = time.perf_counter()
    call()
    return time.perf_counter() - t0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cli", default="build/softdrop", help="the softdrop program")
    parser.add_argument("--droplets", type=int, default=200)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--out", help="JSON file of the timings")
    a = parser.parse_args()

    medium = softdrop.Medium.generate()  # the program's default medium: 500 x 500, overlapping, phi 0.8
    grains = os.path.join(tempfile.mkdtemp(), "medium.json")
    medium.save(grains)
    command = [a.cli, "simulate", "--medium", grains, "--droplets", str(a.droplets), "--seed", "7", "--threads",
               str(a.threads), "--quiet", "--format", "json"]
    python_s, program_s = [], []
    frame = out = None

    def python():
        nonlocal frame
        t0 = time.perf_counter()
        frame = softdrop.simulate_many(medium, a.droplets, seed=7, threads=a.threads)
        python_s.append(time.perf_counter() - t0)

    def program():
        nonlocal out
        t0 = time.perf_counter()
        out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
        program_s.append(time.perf_counter() - t0)

    for repeat in range(a.repeats):  # alternate which goes first, so that neither always follows the other
        for run in (python, program) if repeat % 2 == 0 else (program, python):
            run()
        print(f"repeat {repeat + 1}/{a.repeats}: python {python_s[-1]:.3f} s, program {program_s[-1]:.3f} s",
              flush=True)
    same = [r["steps"] for r in json.loads(out)["runs"]] == frame["steps"].tolist()  # the same droplets
    # The module's own work on top of the run, timed alone: the call's dispatch and checks (a
    # one-step run) and the DataFrame made of the rows.
    rows = softdrop._core._simulate_many(medium, a.droplets, 7, a.threads, softdrop.DropletParams(),
                                         softdrop.RunOptions())
    frame_s = min(timed(lambda: softdrop._runs_frame(rows)) for _ in range(20))
    call_s = min(timed(lambda: softdrop.simulate_many(medium, 1, seed=7, threads=1,
                                                      run=softdrop.RunOptions(max_steps=1))) for _ in range(20))
    py, cli = statistics.median(python_s), statistics.median(program_s)
    result = {
        "droplets": a.droplets, "threads": a.threads, "repeats": a.repeats,
        "python_seconds": python_s, "program_seconds": program_s,
        "python_median_s": py, "program_median_s": cli,
        "overhead_percent": 100.0 * (py - cli) / cli,
        "python_min_s": min(python_s), "program_min_s": min(program_s),
        "frame_seconds": frame_s, "call_seconds": call_s,
        "module_work_percent": 100.0 * (frame_s + call_s) / cli,
        "same_steps": same,
        "machine": platform.processor() or platform.machine(), "cpus": os.cpu_count(),
        "softdrop": softdrop.__version__,
    }
    print(f"median: python {py:.4f} s, program {cli:.4f} s, difference {result['overhead_percent']:+.2f} %; "
          f"the module's own work {1e3 * (frame_s + call_s):.2f} ms = {result['module_work_percent']:.3f} %")
    if a.out:
        with open(a.out + ".tmp", "w") as f:
            json.dump(result, f, indent=2)
            f.write("\n")
        os.replace(a.out + ".tmp", a.out)


if __name__ == "__main__":
    main()
