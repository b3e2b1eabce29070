"""Reference implementations used only by the benchmarks, never by the server or the CLI.

`thesis_rn` and `thesis_rn_data` are the thesis's Relation Network as specified, kept as the
reference row that `benchmarks/bench_thesis_rn.py` trains and scores next to the default
SupportNet (`learning/nets.py`).
"""
