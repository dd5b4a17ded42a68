//! The field's methods since 2017 in mixed teams, over both transports and
//! under network conditions: each agent of a team runs its own method, and
//! advice (actions and shared values) crosses between them as real
//! processes over zenoh as it does in process.

use std::path::Path;

use integration_tests::team_run;
use serde_json::Value;

/// Two mixed teams covering every method since 2017; the first agent of
/// each under network conditions.
const TEAMS: [[&str; 3]; 2] = [
    ["psaf", "rcmp", "peer-learning"],
    ["advice-reuse", "early-advising", "random-advising"],
];

/// A team file of `methods`, the first agent's advice messages lost with
/// probability 0.1 and delayed 1 to 3 ms.
fn team_file(dir: &Path, methods: &[&str]) -> std::path::PathBuf {
    let mut text = String::new();
    for (i, method) in methods.iter().enumerate() {
        text.push_str(&format!("[[agent]]\nalgorithm = \"{method}\"\n"));
        if i == 0 {
            text.push_str("network = { latency = \"uniform:1,3\", loss = 0.1, timeout_ms = 20 }\n");
        }
        text.push('\n');
    }
    let path = dir.join(format!("{}.toml", methods[0]));
    std::fs::write(&path, text).unwrap();
    path
}

/// Every agent's counters at each evaluation (episodes 0, 60 and 120) of
/// one run of `team`.
fn counters(team: &Path, transport: &str, out: &Path) -> Vec<Vec<Value>> {
    let schedule = [
        "--episodes",
        "120",
        "--eval-every",
        "60",
        "--eval-episodes",
        "10",
    ];
    let run = team_run(team, transport, &schedule, out);
    (run["points"].as_array().unwrap().iter())
        .map(|p| p["agents"].as_array().unwrap().clone())
        .collect()
}

/// Every agent's counters at the last evaluation of one run of `team`.
fn last_counters(team: &Path, transport: &str, out: &Path) -> Vec<Value> {
    counters(team, transport, out).pop().unwrap()
}

#[test]
fn every_method_advises_in_a_mixed_team_over_both_transports() {
    let tmp = tempfile::tempdir().unwrap();
    for methods in TEAMS {
        let team = team_file(tmp.path(), &methods);
        for transport in ["in-process", "zenoh"] {
            let out = tmp.path().join(format!("{}-{transport}", methods[0]));
            let agents = last_counters(&team, transport, &out);
            for (method, counters) in methods.iter().zip(&agents) {
                let count = |key: &str| counters[key].as_u64().unwrap();
                let said = format!("{method} over {transport}: {counters}");
                assert!(count("advice_requests") > 0, "asked nothing: {said}");
                assert!(
                    count("advice_replies_received") > 0,
                    "heard nothing: {said}"
                );
                assert!(count("advice_given") > 0, "answered nothing: {said}");
            }
        }
    }
}

/// A homogeneous team of three agents of `method` with the table `extra`,
/// written into `dir` as `name.toml`.
fn homogeneous(dir: &Path, name: &str, method: &str, extra: &str) -> std::path::PathBuf {
    let agent = format!("[[agent]]\nalgorithm = \"{method}\"\n{extra}\n");
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, agent.repeat(3)).unwrap();
    path
}

/// The team's total of counter `key` at the last evaluation.
fn team_total(agents: &[Value], key: &str) -> u64 {
    agents.iter().map(|a| a[key].as_u64().unwrap()).sum()
}

/// `homogeneous(method, extra)` played over `transport`: the agents'
/// counters at the last evaluation.
fn played(dir: &Path, transport: &str, name: &str, method: &str, extra: &str) -> Vec<Value> {
    let team = homogeneous(dir, name, method, extra);
    last_counters(&team, transport, &dir.join(format!("{name}-{transport}")))
}

/// The team reused advice, and a reuse sent nothing: every request has
/// its outcome, and none is a reuse.
fn reused_without_a_message(agents: &[Value], transport: &str) {
    let reused = team_total(agents, "reused_advice");
    let requests = team_total(agents, "advice_requests");
    let outcomes: u64 = ["answered", "declined", "futile", "lost"]
        .iter()
        .map(|o| team_total(agents, &format!("{o}_requests")))
        .sum();
    assert!(reused > 0, "{transport}: nothing reused: {agents:?}");
    assert_eq!(outcomes, requests, "{transport}: {agents:?}");
}

#[test]
fn advice_reuse_plays_kept_advice_without_a_message() {
    let tmp = tempfile::tempdir().unwrap();
    for transport in ["in-process", "zenoh"] {
        let agents = played(tmp.path(), transport, "reuse", "advice-reuse", "");
        reused_without_a_message(&agents, transport);
    }
}

#[test]
fn advice_imitation_collects_advice_and_reuses_its_imitation() {
    let tmp = tempfile::tempdir().unwrap();
    // A budget of 40 (an imitation round every 4 samples), short rounds,
    // and reuse in half the episodes throughout; small DQNs.
    let extra = "ask_budget = 40\ninitial_iterations_per_advice = 2.0\n\
                 periodic_iterations_per_advice = 1.0\nreuse_decay_from = 1000\n\
                 reuse_decay_to = 1000\nhidden = [16]\nwarmup = 32\n";
    for transport in ["in-process", "zenoh"] {
        let agents = played(
            tmp.path(),
            transport,
            "imitation",
            "advice-imitation",
            extra,
        );
        for agent in &agents {
            let spent = agent["ask_spent"].as_u64().unwrap();
            // Its first imitation round comes after 4 samples.
            assert!((4..=40).contains(&spent), "{transport}: {agent}");
        }
        // Reusing the imitation sends nothing.
        reused_without_a_message(&agents, transport);
    }
}

#[test]
fn rcmp_asks_while_its_heads_disagree() {
    let tmp = tempfile::tempdir().unwrap();
    // Small DQNs of 5 heads, whose uncertainty is infinite until their
    // first learning step (after 32 stored transitions).
    let requests = |transport: &str, name: &str, threshold: &str| -> Vec<Vec<u64>> {
        let extra = format!("hidden = [16]\nwarmup = 32\nuncertainty_threshold = {threshold}\n");
        let team = homogeneous(tmp.path(), name, "rcmp", &extra);
        let out = tmp.path().join(format!("{name}-{transport}"));
        (counters(&team, transport, &out).iter())
            .map(|agents| {
                agents
                    .iter()
                    .map(|a| a["advice_requests"].as_u64().unwrap())
                    .collect()
            })
            .collect()
    };
    for transport in ["in-process", "zenoh"] {
        // No variance of learning heads reaches 1e12: each agent asks in
        // its warm-up, then never.
        let certain = requests(transport, "certain", "1e12");
        let said = format!("{transport}: {certain:?}");
        assert!(certain[1].iter().all(|r| (1..=64).contains(r)), "{said}");
        assert_eq!(certain[1], certain[2], "{said}");
        // At its threshold, the heads disagree long after: it asks on.
        let asking = requests(transport, "asking", "0.001");
        let said = format!("{transport}: {asking:?}");
        assert!(
            asking[2].iter().zip(&asking[1]).all(|(end, mid)| end > mid),
            "{said}"
        );
    }
}

#[test]
fn ef_ontl_transfers_experience_between_its_agents() {
    let tmp = tempfile::tempdir().unwrap();
    // Transfers every 20 episodes (at the ends of 21, 41, 61, 81 and 101),
    // 8 tuples learned of up to 64 sent; small DQNs.
    let extra = "interval = 20\nbuffer = 64\ntransfer_batch = 8\nhidden = [16]\nwarmup = 32\n";
    let team = homogeneous(tmp.path(), "ef-ontl", "ef-ontl", extra);
    for transport in ["in-process", "zenoh"] {
        let out = tmp.path().join(format!("ef-ontl-{transport}"));
        let agents = last_counters(&team, transport, &out);
        // Its budget is the tuples received: five transfers, each of at
        // most 64 tuples (its buffer) to each of two receivers.
        let received = team_total(&agents, "give_spent");
        assert!(
            (1..=5 * 2 * 64).contains(&received),
            "{transport}: {agents:?}"
        );
        // Standings after episodes 20, 40, ..., 120 (six messages each),
        // candidates after 21, 41, 61, 81 and 101 (two each).
        let messages = team_total(&agents, "advising_messages");
        assert_eq!(messages, 6 * 6 + 5 * 2, "{transport}: {agents:?}");
        // Nobody asks or answers.
        assert_eq!(team_total(&agents, "advice_requests"), 0);
        assert_eq!(team_total(&agents, "advice_given"), 0);
        if transport == "in-process" {
            assert!(received >= 5 * 2 * 8, "{agents:?}");
        }
    }
    // One seed, the same run files.
    let schedule = [
        "--episodes",
        "60",
        "--eval-every",
        "30",
        "--eval-episodes",
        "5",
    ];
    let [a, b] = ["a", "b"].map(|n| tmp.path().join(format!("ef-ontl-{n}")));
    assert_eq!(
        team_run(&team, "in-process", &schedule, &a),
        team_run(&team, "in-process", &schedule, &b)
    );
}

#[test]
fn psaf_partakers_take_the_values_sharers_more_confident_send() {
    let tmp = tempfile::tempdir().unwrap();
    for transport in ["in-process", "zenoh"] {
        let agents = played(tmp.path(), transport, "psaf", "psaf", "");
        let taken = team_total(&agents, "ask_spent");
        let shared = team_total(&agents, "advice_given");
        let answered = team_total(&agents, "answered_requests");
        let declined = team_total(&agents, "declined_requests");
        assert!(taken > 0, "{transport}: no values taken: {agents:?}");
        // A partaker spends its budget only on a request that brought a
        // value, and a sharer less confident than the partaker declines.
        assert!(
            taken <= answered && answered <= shared,
            "{transport}: {agents:?}"
        );
        assert!(declined > 0, "{transport}: every sharer shared: {agents:?}");
    }
}

#[test]
fn peer_learning_follows_its_choice_for_the_window() {
    let tmp = tempfile::tempdir().unwrap();
    for transport in ["in-process", "zenoh"] {
        // Advising messages per request: each request goes to both peers
        // (2 requests, 2 replies) unless the agent follows one peer, asked
        // alone; following its own choice asks nobody.
        let per_request = |window: u32| {
            let name = format!("peers-{window}");
            let extra = format!("follow_steps = {window}\n");
            let agents = played(tmp.path(), transport, &name, "peer-learning", &extra);
            let messages = team_total(&agents, "advising_messages") as f64;
            let requests = team_total(&agents, "advice_requests") as f64;
            assert!(requests > 0.0, "{transport}: no request: {agents:?}");
            (messages / requests, requests)
        };
        let (each, asked_each) = per_request(1);
        let (window, asked_window) = per_request(10);
        assert!(each > 3.5, "{transport}: {each} messages per request");
        assert!(window < 3.0, "{transport}: {window} messages per request");
        assert!(
            asked_window < asked_each,
            "{transport}: its own choice asks nobody"
        );
    }
}

#[test]
fn an_announced_exhausted_advisor_is_asked_no_more() {
    let tmp = tempfile::tempdir().unwrap();
    for transport in ["in-process", "zenoh"] {
        let run = |announce: bool| {
            let name = format!("announce-{announce}");
            let extra = format!("give_budget = 20\nannounce_exhausted = {announce}\n");
            played(tmp.path(), transport, &name, "early-advising", &extra)
        };
        let (quiet, told) = (run(false), run(true));
        let futile = |agents: &[Value]| team_total(agents, "futile_requests");
        let messages = |agents: &[Value]| team_total(agents, "advising_messages");
        assert!(futile(&quiet) > 0, "{transport}: {quiet:?}");
        // Over zenoh a request may cross the announcement in flight.
        assert!(
            futile(&told) * 10 <= futile(&quiet),
            "{transport}: {} futile requests announced, {} not",
            futile(&told),
            futile(&quiet)
        );
        assert!(
            messages(&told) < messages(&quiet),
            "{transport}: the announcement saves no message"
        );
    }
}
