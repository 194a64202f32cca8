"""Arbor's analysis: the report's sections and the helpers they share, for analysis/report and analysis/studies/.

results.py       the sweep's rows as a DataFrame, the statistics (mean with t-based 95 % CI, log-log fit), tables
                 and figures; the files themselves are read by arbor_files (python/arbor_files.py)
html_report.py   report.md as one self-contained report.html
the sections     one module per report section, each with make(df, out_dir, results_dir) -> [Section]:
                 configurations, dataset_accuracy, failures, complexity, accuracy, paired, consistency, association, hypotheses,
                 smoother_table, step_series, threads, trajectory. Each also runs on its own:
                 PYTHONPATH=analysis /usr/bin/python3 -m arbor_analysis.accuracy RESULTS_DIR [--out DIR]
"""

import os
import sys

# arbor_files, the one reader of Arbor's files, lives beside the `arbor` package in python/ (the build copies
# both to build/python). Appended, not inserted, so that a built `arbor` on PYTHONPATH still comes before the
# source tree's python/arbor, which cannot import without its compiled part.
_PYTHON_DIR = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "python")
if _PYTHON_DIR not in sys.path:
    sys.path.append(_PYTHON_DIR)
