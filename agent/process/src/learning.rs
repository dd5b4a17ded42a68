//! The learning side of the process: the library's agent for the current
//! run, its position in the observation stream and the shares and batches
//! waiting for it. Pure state, driven by the tasks that hold it under a
//! lock.

use agent::{
    AdviceReport, Agent, AgentConfig, Answer, Answers, Batch, Decision, Observation, Sends,
    Snapshot,
};
use proto::{
    Action, AdviceOutcome, AdviceRequest, Body, DropReason, ExperienceBatch, FeaturedRequest,
    Features, Header, Mode, SharedEpisode,
};

use crate::child::ChildCommands;
use crate::learner_pipe::PipeLearner;
use crate::order::{ObservationOrder, Position};
use crate::shares::PendingShares;
use crate::strategy_pipe::PipeStrategy;

/// What the process does after an accepted observation.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    /// Publish this action (a kicker's choice), or nothing.
    Act(Option<Action>),
    /// Ask for advice, then call [`Learning::complete`] (boxed: the rare
    /// step that carries a state and its features).
    Ask(Box<Ask>),
    /// The episode ended: publish what it sends unasked (receiver, what).
    End(Sends),
}

/// An advice request to send.
#[derive(Clone, Debug, PartialEq)]
pub struct Ask {
    /// The advisors, already restricted to the live ones.
    pub to: Vec<u8>,
    /// The request.
    pub request: AdviceRequest,
    /// HFO's features of the state, where the observation carried them.
    pub features: Features,
    /// Which learner asked (see [`Learning::complete`]).
    epoch: u64,
}

impl Ask {
    /// The message sent to each advisor: the request, with the features
    /// where there are some.
    pub fn body(&self) -> Body {
        match self.features.is_empty() {
            true => Body::AdviceRequest(self.request),
            false => Body::FeaturedRequest(FeaturedRequest {
                request: self.request,
                features: self.features,
            }),
        }
    }
}

/// How far the observations of the current run were processed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Progress {
    /// The run of the last reset.
    pub run: u32,
    /// Its last episode whose terminal frame was processed.
    pub finished: Option<u32>,
}

/// Agent `id`'s learning state.
#[derive(Debug)]
pub struct Learning {
    id: u8,
    team_size: u8,
    /// A learner process in place of SARSA(lambda) and a strategy process
    /// making algorithm `external`'s decisions, started at each reset.
    children: ChildCommands,
    agent: Option<Agent>,
    run: u32,
    /// Counts resets and loads, so that answers to an older learner's
    /// request are not fed to a newer one.
    epoch: u64,
    stream: ObservationOrder,
    shares: PendingShares,
    batches: PendingShares<Batch>,
}

impl Learning {
    /// Agent `id` of a team of `team_size`, waiting for its first reset,
    /// with its learner and strategy processes `children` where given.
    pub fn new(id: u8, team_size: u8, children: ChildCommands) -> Self {
        Self {
            id,
            team_size,
            children,
            agent: None,
            run: 0,
            epoch: 0,
            stream: ObservationOrder::default(),
            shares: PendingShares::default(),
            batches: PendingShares::default(),
        }
    }

    /// Starts run `run` with a fresh agent from `config` (an `AgentConfig`
    /// encoded with `proto::encode_settings`) and `seed`; on error the
    /// current state is kept.
    pub fn reset(&mut self, run: u32, seed: u64, config: &[u8]) -> Result<(), String> {
        let config: AgentConfig = proto::decode_settings(config)
            .map_err(|e| format!("agent config does not decode: {e}"))?;
        config.validate().map_err(|e| e.to_string())?;
        let (id, team_size) = (self.id.into(), self.team_size.into());
        let external = config.algorithm.name().is_external();
        match (&self.children.strategy, external) {
            (None, true) => return Err(NO_STRATEGY.into()),
            (Some(_), false) => {
                return Err(format!(
                    "this agent runs a strategy process, so its algorithm must be \
                     `external`, not `{}`",
                    config.algorithm.name()
                ));
            }
            _ => {}
        }
        if self.children != ChildCommands::default() {
            // The previous run's child processes end before the next start.
            self.agent = None;
        }
        let agent = match &self.children.learner {
            None => Agent::new(id, team_size, config, seed),
            Some(command) => {
                let learner = PipeLearner::start(command, self.id, self.team_size, run, seed)?;
                Agent::with_learner(id, team_size, config, seed, Box::new(learner))
            }
        }
        .map_err(|e| e.to_string())?;
        let agent = match &self.children.strategy {
            None => agent,
            Some(command) => {
                let strategy = PipeStrategy::start(command, self.id, self.team_size, run, seed)?;
                agent.with_strategy(Box::new(strategy))
            }
        };
        *self = Self {
            agent: Some(agent),
            run,
            epoch: self.epoch + 1,
            ..Self::new(self.id, self.team_size, std::mem::take(&mut self.children))
        };
        Ok(())
    }

    /// Makes the run just reset start at `episode`: an agent that joins a
    /// running run (a newcomer or a restart) has finished the episodes
    /// before it, for commands that wait for them, and drops their frames.
    pub fn join_at(&mut self, episode: u32) {
        self.stream = ObservationOrder::joining_at(episode);
    }

    /// Replaces the learned state with a snapshot (the bytes of a snapshot
    /// file); on error the current state is kept.
    pub fn load(&mut self, snapshot: &[u8]) -> Result<(), String> {
        let agent = self.agent.as_mut().ok_or(NO_RUN)?;
        let snapshot = Snapshot::decode(snapshot).map_err(|e| e.to_string())?;
        agent.restore(snapshot).map_err(|e| e.to_string())?;
        self.epoch += 1;
        Ok(())
    }

    /// The agent of the current run, if reset.
    pub fn agent(&self) -> Result<&Agent, String> {
        self.agent.as_ref().ok_or_else(|| NO_RUN.to_owned())
    }

    /// How far the current run was processed.
    pub fn progress(&self) -> Progress {
        Progress {
            run: self.run,
            finished: self.stream.finished(),
        }
    }

    /// One observation, in stream order: begins, plays or ends an episode.
    /// `reachable(j)` says whether agent `j` can be asked now.
    pub fn observe(
        &mut self,
        header: &Header,
        obs: &proto::AgentFrame,
        reachable: &dyn Fn(usize) -> bool,
    ) -> Result<Step, DropReason> {
        if obs.agent != self.id || !self.fits(&obs.features) {
            return Err(DropReason::Malformed);
        }
        let agent = match self.agent.as_mut() {
            Some(a) if header.run == self.run => a,
            _ => return Err(DropReason::Stale),
        };
        let position = self
            .stream
            .accept(header.episode, header.frame, obs.is_terminal())?;
        let finished = self.stream.finished();
        if position == Position::NewEpisode {
            agent.begin_episode(obs.mode);
            learn_due(agent, &mut self.shares, &mut self.batches, finished);
        }
        if let Some(outcome) = obs.outcome {
            agent.end_episode(outcome);
            let shares = agent.take_shared();
            learn_due(agent, &mut self.shares, &mut self.batches, finished);
            return Ok(Step::End(shares));
        }
        let me = Observation {
            state: obs.state,
            features: obs.features,
            can_kick: obs.can_kick,
            position: obs
                .positions
                .get(usize::from(self.id))
                .copied()
                .unwrap_or_default(),
        };
        Ok(
            match agent.act_begin(&me, obs.reward, &obs.positions, reachable) {
                Decision::Act(action) => Step::Act(obs.can_kick.then_some(action)),
                Decision::Ask {
                    to,
                    state,
                    features,
                    along,
                } => Step::Ask(Box::new(Ask {
                    // Ids come from a team of at most u8::MAX agents.
                    to: to
                        .into_iter()
                        .filter_map(|j| u8::try_from(j).ok())
                        .collect(),
                    request: AdviceRequest {
                        from: self.id,
                        state,
                        along,
                    },
                    features,
                    epoch: self.epoch,
                })),
            },
        )
    }

    /// Completes the frame that asked with the advice that arrived in
    /// `replies` replies; `None` if the learner was reset or loaded meanwhile.
    pub fn complete(&mut self, ask: &Ask, answers: &Answers, replies: u64) -> Option<Action> {
        let agent = self.agent.as_mut().filter(|_| ask.epoch == self.epoch)?;
        Some(agent.act_complete(answers, replies))
    }

    /// A shared episode: replayed once this agent has finished that episode
    /// itself and is not evaluating.
    pub fn receive_share(
        &mut self,
        header: &Header,
        share: SharedEpisode,
    ) -> Result<(), DropReason> {
        let SharedEpisode {
            from,
            to,
            transitions,
        } = share;
        self.check_share(header, from, to)?;
        self.shares.push(from.into(), header.episode, transitions)?;
        self.learn_due();
        Ok(())
    }

    /// A batch of experience: learned once this agent has finished that
    /// episode itself and is not evaluating.
    pub fn receive_batch(
        &mut self,
        header: &Header,
        batch: ExperienceBatch,
    ) -> Result<(), DropReason> {
        let ExperienceBatch {
            from,
            to,
            transitions,
            notes,
            standing,
        } = batch;
        self.check_share(header, from, to)?;
        let batch = Batch {
            transitions,
            notes,
            standing,
        };
        self.batches.push(from.into(), header.episode, batch)?;
        self.learn_due();
        Ok(())
    }

    /// Whether what agent `from` sent agent `to` unasked is for this agent
    /// in the current run.
    fn check_share(&self, header: &Header, from: u8, to: u8) -> Result<(), DropReason> {
        if to != self.id || from == self.id || from >= self.team_size {
            return Err(DropReason::Malformed);
        }
        match self.agent {
            Some(_) if header.run == self.run => Ok(()),
            _ => Err(DropReason::Stale),
        }
    }

    /// Learns what is due of what others sent.
    fn learn_due(&mut self) {
        if let Some(agent) = self.agent.as_mut() {
            let finished = self.stream.finished();
            learn_due(agent, &mut self.shares, &mut self.batches, finished);
        }
    }

    /// An advisee's report of how a decision on this agent's advice turned
    /// out, in the run of `header`.
    pub fn hear_advice_outcome(
        &mut self,
        header: &Header,
        report: &AdviceOutcome,
    ) -> Result<(), DropReason> {
        let from = report.from;
        if report.to != self.id || from == self.id || from >= self.team_size {
            return Err(DropReason::Malformed);
        }
        match self.agent.as_mut() {
            Some(a) if header.run == self.run => {
                a.hear_advice_outcome(from.into(), report.followed, report.advantage);
                Ok(())
            }
            _ => Err(DropReason::Stale),
        }
    }

    /// The reports of advice outcomes the agent has to send.
    pub fn take_reports(&mut self) -> Vec<AdviceReport> {
        (self.agent.as_mut())
            .map(Agent::take_reports)
            .unwrap_or_default()
    }

    /// Whether the agent has its spent give budget to announce (once).
    pub fn take_announcement(&mut self) -> bool {
        self.agent.as_mut().is_some_and(Agent::take_announcement)
    }

    /// Agent `from` announced its give budget spent in the run of `header`.
    pub fn hear_exhausted(&mut self, header: &Header, from: u8) -> Result<(), DropReason> {
        if from >= self.team_size {
            return Err(DropReason::Malformed);
        }
        match self.agent.as_mut() {
            Some(a) if header.run == self.run => {
                a.hear_exhausted(usize::from(from));
                Ok(())
            }
            _ => Err(DropReason::Stale),
        }
    }

    /// Agent `j`'s process joined (again): it is asked until it announces
    /// its budget spent.
    pub fn peer_joined(&mut self, j: u8) {
        if let Some(a) = self.agent.as_mut() {
            a.peer_joined(usize::from(j));
        }
    }

    /// The answer to a request of the current run, with the asker's HFO
    /// `features` of its state if it sent them.
    pub fn advise(
        &mut self,
        header: &Header,
        request: &AdviceRequest,
        features: &Features,
    ) -> Result<Answer, DropReason> {
        if request.from == self.id || request.from >= self.team_size || !self.fits(features) {
            return Err(DropReason::Malformed);
        }
        let (state, features) = (&request.state, features.as_slice());
        match self.agent.as_mut() {
            Some(a) if header.run == self.run => {
                Ok(a.answer(request.from.into(), state, features, request.along))
            }
            _ => Err(DropReason::Stale),
        }
    }

    /// Whether `features` are none, or HFO's set of this team: as many as
    /// its size gives, every one finite.
    fn fits(&self, features: &Features) -> bool {
        let values = features.as_slice();
        values.is_empty()
            || values.len() == proto::hfo_feature_count(self.team_size.into())
                && values.iter().all(|x| x.is_finite())
    }
}

/// Why a command needs a reset first.
const NO_RUN: &str = "no run started: the agent has not been reset";

/// Why algorithm `external` cannot run here.
const NO_STRATEGY: &str = "algorithm `external` takes its decisions from a strategy process, \
    and this agent runs none: start it with `--strategy` (a team file's `strategy_process`; \
    docs/strategies.md)";

/// Learns the shared episodes, then the batches, that are due.
fn learn_due(
    agent: &mut Agent,
    shares: &mut PendingShares,
    batches: &mut PendingShares<Batch>,
    finished: Option<u32>,
) {
    let training = agent.mode() == Mode::Training;
    for (_, transitions) in shares.take_ready(finished, training) {
        agent.receive_shared(&transitions);
    }
    for (from, batch) in batches.take_ready(finished, training) {
        if !agent.receive_batch(from, &batch) {
            tracing::debug!(from, "a batch this agent's learner cannot learn");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use agent::{Share, Transition};
    use proto::{Along, EpisodeOutcome};

    /// The wire form of the `AgentConfig` these JSON settings describe.
    fn config(json: &str) -> Vec<u8> {
        let config: AgentConfig = serde_json::from_str(json).unwrap();
        proto::encode_settings(&config).unwrap()
    }

    fn sharing() -> Vec<u8> {
        config(r#"{"algorithm": "episode-sharing"}"#)
    }

    fn header(run: u32, episode: u32, frame: u32) -> Header {
        Header::new(1, run, episode, frame)
    }

    /// Agent `agent`'s frame; a `terminal` one ends the episode with a
    /// goal (`reward` 1) or a time-out (0).
    fn obs(agent: u8, kick: bool, terminal: bool, reward: f64) -> proto::AgentFrame {
        let ended = match reward > 0.0 {
            true => EpisodeOutcome::Goal,
            false => EpisodeOutcome::OutOfTime,
        };
        proto::AgentFrame {
            agent,
            mode: Mode::Training,
            state: [0.1, 0.2, 0.3, 0.4, 0.5, if kick { 0.6 } else { -0.6 }],
            features: Features::NONE,
            can_kick: kick,
            positions: vec![[0.0, 0.0], [1.0, 1.0]],
            reward,
            outcome: terminal.then_some(ended),
        }
    }

    fn reset(id: u8) -> Learning {
        let mut l = Learning::new(id, 2, ChildCommands::default());
        l.reset(3, 9, &sharing()).unwrap();
        l
    }

    /// Plays a goal episode of two Move frames: the shares it produces.
    fn goal_episode(l: &mut Learning, episode: u32) -> Sends {
        let id = l.id;
        let all = |_| true;
        assert_eq!(
            l.observe(&header(3, episode, 0), &obs(id, false, false, 0.0), &all),
            Ok(Step::Act(None))
        );
        assert_eq!(
            l.observe(&header(3, episode, 1), &obs(id, false, false, 0.0), &all),
            Ok(Step::Act(None))
        );
        match l.observe(&header(3, episode, 2), &obs(id, false, true, 1.0), &all) {
            Ok(Step::End(shares)) => shares,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn bad_resets_keep_the_current_state() {
        let mut l = Learning::new(0, 2, ChildCommands::default());
        assert!(l.agent().is_err());
        assert!(l.reset(0, 1, b"{").unwrap_err().contains("does not decode"));
        let mut long = sharing();
        long.push(0);
        assert!(
            l.reset(0, 1, &long)
                .unwrap_err()
                .contains("does not decode")
        );
        assert!(
            l.reset(0, 1, &config(r#"{"alpha": 2.0}"#))
                .unwrap_err()
                .contains("alpha")
        );
        assert!(l.agent().is_err());
        assert!(l.load(&[]).unwrap_err().contains("not been reset"));
    }

    #[test]
    fn every_strategy_crosses_the_wire() {
        for name in agent::Algorithm::all() {
            let mut sent = AgentConfig::of(name, agent::Profile::Paper);
            if sent.algorithm.reachable().is_some() {
                let one = serde_json::json!({"agents": [1]});
                sent.algorithm.set("reachable", one).unwrap();
            }
            let bytes = proto::encode_settings(&sent).unwrap();
            assert_eq!(proto::decode_settings::<AgentConfig>(&bytes), Ok(sent));
            let reset = Learning::new(0, 2, ChildCommands::default()).reset(0, 1, &bytes);
            // `external` needs its strategy process.
            assert_eq!(reset.is_err(), name.is_external(), "{name}");
        }
    }

    #[test]
    fn a_strategy_process_goes_with_algorithm_external_only() {
        let external = config(r#"{"algorithm": "external"}"#);
        let error =
            (Learning::new(0, 2, ChildCommands::default()).reset(0, 1, &external)).unwrap_err();
        assert!(error.contains("--strategy"), "{error}");
        let children = ChildCommands {
            strategy: Some(crate::child::ChildCommand {
                argv: vec!["python3".into(), "s.py".into()],
                dir: None,
                timeout: std::time::Duration::from_secs(1),
            }),
            ..ChildCommands::default()
        };
        let error = Learning::new(0, 2, children)
            .reset(0, 1, &sharing())
            .unwrap_err();
        assert!(error.contains("not `episode-sharing`"), "{error}");
    }

    #[test]
    fn loads_a_snapshot_and_refuses_bad_bytes() {
        let (mut trained, mut fresh) = (reset(0), reset(0));
        goal_episode(&mut trained, 0);
        let snapshot = trained.agent().unwrap().snapshot();
        let before = fresh.agent().unwrap().digest();
        assert!(fresh.load(b"not a snapshot").is_err());
        let mut bytes = snapshot.encode().unwrap();
        bytes.pop();
        assert!(fresh.load(&bytes).is_err());
        assert_eq!(fresh.agent().unwrap().digest(), before);
        fresh.load(&snapshot.encode().unwrap()).unwrap();
        assert_eq!(fresh.agent().unwrap().digest(), snapshot.digest());
    }

    #[test]
    fn observations_of_other_runs_agents_or_before_a_reset_are_dropped() {
        let all = |_| true;
        let mut fresh = Learning::new(0, 2, ChildCommands::default());
        assert_eq!(
            fresh.observe(&header(0, 0, 0), &obs(0, true, false, 0.0), &all),
            Err(DropReason::Stale)
        );
        let mut l = reset(0);
        let before = l.agent().unwrap().digest();
        assert_eq!(
            l.observe(&header(2, 0, 0), &obs(0, true, false, 0.0), &all),
            Err(DropReason::Stale)
        );
        assert_eq!(
            l.observe(&header(3, 0, 0), &obs(1, true, false, 0.0), &all),
            Err(DropReason::Malformed)
        );
        assert_eq!(l.agent().unwrap().digest(), before);
        assert_eq!(
            l.progress(),
            Progress {
                run: 3,
                finished: None
            }
        );
    }

    #[test]
    fn shares_are_published_as_data_and_replayed_after_the_own_terminal_frame() {
        let (mut a, mut b) = (reset(0), reset(1));
        let shares = goal_episode(&mut a, 0);
        assert_eq!(shares.len(), 1);
        let Some((to, Share::Episode(transitions))) = shares.into_iter().next() else {
            panic!("no episode shared");
        };
        assert_eq!((to, transitions.len()), (1, 2));
        let share = SharedEpisode {
            from: 0,
            to: 1,
            transitions,
        };
        // b has not finished episode 0 yet: the share waits.
        let all = |_| true;
        b.observe(&header(3, 0, 0), &obs(1, false, false, 0.0), &all)
            .unwrap();
        let before = b.agent().unwrap().digest();
        b.receive_share(&header(3, 0, 0), share.clone()).unwrap();
        assert_eq!(b.agent().unwrap().counters().shared_received, 0);
        assert_eq!(
            b.receive_share(&header(3, 0, 0), share.clone()),
            Err(DropReason::Duplicate)
        );
        assert_eq!(
            b.receive_share(&header(4, 1, 0), share.clone()),
            Err(DropReason::Stale)
        );
        let wrong = SharedEpisode { to: 0, ..share };
        assert_eq!(
            b.receive_share(&header(3, 1, 0), wrong),
            Err(DropReason::Malformed)
        );
        assert_eq!(b.agent().unwrap().digest(), before);
        b.observe(&header(3, 0, 1), &obs(1, false, true, 0.0), &all)
            .unwrap();
        assert_eq!(b.agent().unwrap().counters().shared_received, 2);
        assert_eq!(b.progress().finished, Some(0));
    }

    #[test]
    fn batches_wait_like_shares_and_reports_are_checked() {
        let mut b = reset(1);
        let t = Transition {
            state: [0.5; 6],
            action: Action::Shoot,
            reward: 1.0,
            next: None,
        };
        let batch = |from, to| ExperienceBatch {
            from,
            to,
            transitions: vec![t; 3],
            notes: Vec::new(),
            standing: None,
        };
        let all = |_| true;
        b.observe(&header(3, 0, 0), &obs(1, false, false, 0.0), &all)
            .unwrap();
        b.receive_batch(&header(3, 0, 0), batch(0, 1)).unwrap();
        assert_eq!(b.agent().unwrap().counters().shared_received, 0);
        assert_eq!(
            b.receive_batch(&header(3, 0, 0), batch(0, 1)),
            Err(DropReason::Duplicate)
        );
        for (from, to) in [(0, 0), (1, 1), (2, 1)] {
            assert_eq!(
                b.receive_batch(&header(3, 1, 0), batch(from, to)),
                Err(DropReason::Malformed)
            );
        }
        assert_eq!(
            b.receive_batch(&header(4, 1, 0), batch(0, 1)),
            Err(DropReason::Stale)
        );
        // Taken once its own episode 0 ends (its SARSA learner cannot learn
        // a batch, but it counts what arrived).
        b.observe(&header(3, 0, 1), &obs(1, false, true, 0.0), &all)
            .unwrap();
        assert_eq!(b.agent().unwrap().counters().shared_received, 3);
        let mut report = |from, to, run| {
            let r = AdviceOutcome {
                from,
                to,
                followed: true,
                advantage: 0.5,
            };
            b.hear_advice_outcome(&header(run, 1, 0), &r)
        };
        assert_eq!(report(0, 1, 3), Ok(()));
        assert_eq!(report(1, 1, 3), Err(DropReason::Malformed));
        assert_eq!(report(0, 0, 3), Err(DropReason::Malformed));
        assert_eq!(report(0, 1, 4), Err(DropReason::Stale));
        assert!(b.take_reports().is_empty());
    }

    #[test]
    fn advice_for_another_run_or_from_oneself_is_refused() {
        let mut l = reset(0);
        let request = |from| AdviceRequest {
            from,
            state: [0.0; 6],
            along: Along::Nothing,
        };
        let none = Features::NONE;
        assert_eq!(
            l.advise(&header(3, 0, 0), &request(1), &none),
            Ok(Answer::Action(proto::AdviceAnswer::Declined))
        );
        assert_eq!(
            l.advise(&header(2, 0, 0), &request(1), &none),
            Err(DropReason::Stale)
        );
        assert_eq!(
            l.advise(&header(3, 0, 0), &request(0), &none),
            Err(DropReason::Malformed)
        );
        assert_eq!(
            l.advise(&header(3, 0, 0), &request(2), &none),
            Err(DropReason::Malformed)
        );
        // HFO's features of a team of two are 21 finite numbers.
        let features = |n, x| Features::new(&vec![x; n]).unwrap();
        assert!(
            l.advise(&header(3, 0, 0), &request(1), &features(21, 0.5))
                .is_ok()
        );
        for odd in [features(27, 0.5), features(21, f32::INFINITY)] {
            assert_eq!(
                l.advise(&header(3, 0, 0), &request(1), &odd),
                Err(DropReason::Malformed)
            );
        }
    }

    #[test]
    fn an_hfo_learner_asks_with_the_features_it_observed() {
        let config = config(r#"{"strategy": "torrey", "learner": "dqn", "observation": "hfo"}"#);
        let mut l = Learning::new(0, 2, ChildCommands::default());
        l.reset(0, 1, &config).unwrap();
        let features = Features::new(&[0.25; 21]).unwrap();
        let kick = proto::AgentFrame {
            features,
            ..obs(0, true, false, 0.0)
        };
        let Ok(Step::Ask(ask)) = l.observe(&header(0, 0, 0), &kick, &|_| true) else {
            panic!("no request");
        };
        let request = FeaturedRequest {
            request: ask.request,
            features,
        };
        assert_eq!(ask.body(), Body::FeaturedRequest(request));
        // Another team's features are dropped, the frame unseen.
        let odd = proto::AgentFrame {
            features: Features::new(&[0.25; 27]).unwrap(),
            ..kick
        };
        assert_eq!(
            l.observe(&header(0, 0, 1), &odd, &|_| true),
            Err(DropReason::Malformed)
        );
    }

    #[test]
    fn asks_live_advisors_and_ignores_answers_for_a_replaced_learner() {
        let config = config(r#"{"strategy": "torrey"}"#);
        let mut l = Learning::new(0, 2, ChildCommands::default());
        l.reset(0, 1, &config).unwrap();
        // Torrey students ask their teacher at every fresh kick state, if alive.
        let kick = obs(0, true, false, 0.0);
        let step = l.observe(&header(0, 0, 0), &kick, &|_| false).unwrap();
        assert!(
            matches!(step, Step::Act(Some(a)) if a.is_kick()),
            "{step:?}"
        );
        let Ok(Step::Ask(ask)) = l.observe(&header(0, 0, 1), &kick, &|_| true) else {
            panic!("no request");
        };
        assert_eq!(ask.to, vec![1]);
        assert_eq!(ask.request.from, 0);
        assert_eq!(
            l.complete(&ask, &advice(1, Action::PassFar), 1),
            Some(Action::PassFar)
        );
        let Ok(Step::Ask(ask)) = l.observe(&header(0, 1, 0), &kick, &|_| true) else {
            panic!("no request");
        };
        l.reset(1, 1, &config).unwrap();
        assert_eq!(l.complete(&ask, &advice(1, Action::Shoot), 1), None);
    }

    fn advice(advisor: usize, action: Action) -> Answers {
        Answers {
            advice: vec![agent::Advice { advisor, action }],
            ..Answers::default()
        }
    }
}
