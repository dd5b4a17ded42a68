//! Experiment protocol, statistics and reports (filled by the agents issue).
