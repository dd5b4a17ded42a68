//! DQNs reading HFO's features (`observation = "hfo"`, one of them an
//! ensemble of heads asking by its uncertainty) beside one reading the
//! paper's, over both transports: the features reach the agents that read
//! them, in process from the env and over zenoh in env-server's
//! observations, and go with their advice requests to advisors that value
//! the askers' states by them.

use std::path::Path;

use integration_tests::team_run;
use serde_json::Value;

/// A small DQN of `algorithm` that trains from its eighth decision,
/// reading `observation`.
fn agent(algorithm: &str, observation: &str) -> String {
    format!(
        "[[agent]]\nalgorithm = \"{algorithm}\"\nlearner = \"dqn\"\nobservation = \"{observation}\"\n\
         hidden = [16, 8]\nbatch = 8\nreplay = 200\nwarmup = 8\ntarget_every = 5\n\
         epsilon_decay = 100\n"
    )
}

/// Every agent's counters at the last evaluation of one run of `team`.
fn last_counters(team: &Path, transport: &str, out: &Path) -> Vec<Value> {
    let schedule = [
        "--episodes",
        "60",
        "--eval-every",
        "30",
        "--eval-episodes",
        "5",
    ];
    let run = team_run(team, transport, &schedule, out);
    let points = run["points"].as_array().unwrap();
    points.last().unwrap()["agents"].as_array().unwrap().clone()
}

#[test]
fn dqns_reading_hfos_features_learn_and_advise_over_both_transports() {
    let tmp = tempfile::tempdir().unwrap();
    let team = tmp.path().join("team.toml");
    let text = [
        agent("adhoc-td", "hfo"),
        agent("rcmp", "hfo"),
        agent("adhoc-td", "paper"),
    ];
    let text = text.join("\n");
    std::fs::write(&team, text).unwrap();
    for transport in ["in-process", "zenoh"] {
        let agents = last_counters(&team, transport, &tmp.path().join(transport));
        let count = |agent: &Value, key: &str| agent[key].as_u64().unwrap();
        // Without the features an HFO agent stores no decision, never
        // trains and has no values to advise with; with them in its
        // observations and in its teammate's requests it does.
        for (i, agent) in agents[..2].iter().enumerate() {
            let said = format!("{transport}, agent {i}: {agent}");
            assert!(count(agent, "advice_requests") > 0, "{said}");
            assert!(count(agent, "advice_given") > 0, "{said}");
        }
        let paper = &agents[2];
        assert!(count(paper, "advice_requests") > 0, "{transport}: {paper}");
    }
}
