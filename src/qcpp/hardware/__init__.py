"""Device models (:mod:`qcpp.hardware.device`): coupling maps, native gates, error rates, durations and readout
errors of compile targets; the calibration snapshots of named devices are the JSON files in ``data/``."""
