//! The in-process backend: all agents in one `Vec`, advising by direct calls
//! in a fixed order, so a run is bit-for-bit deterministic.

use proto::{
    Action, AdviceOutcome, AdviceReply, AdviceRequest, Along, Body, Envelope, EpisodeOutcome,
    Exhausted, ExperienceBatch, FeaturedRequest, Features, Header, Mode, SharedEpisode, State,
    ValuesReply,
};

use crate::agent::{Agent, Observation};
use crate::exchange::{AdviceExchange, Answer, Answers, Share};
use crate::link::{Leg, Link, Message};

/// A team that does not fit together, or a frame of the wrong size.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TeamError {
    /// The agent at `index` was built with another id.
    #[error("the agent at index {index} has id {id}")]
    Id {
        /// Position in the team.
        index: usize,
        /// Its id.
        id: usize,
    },
    /// An agent was built for another team size.
    #[error("agent {id} was built for a team of {built_for}, the team has {size}")]
    Size {
        /// The agent.
        id: usize,
        /// Team size given at its construction.
        built_for: usize,
        /// Actual team size.
        size: usize,
    },
    /// A frame did not carry one observation per agent.
    #[error("expected {expected} observations, got {got}")]
    Observations {
        /// Team size.
        expected: usize,
        /// Observations given.
        got: usize,
    },
}

/// Every agent of a team, driven frame by frame.
///
/// In a frame, agents act in id order; an advisee asks its advisors in the
/// order of its reachable set, each advisor answering from its current state.
/// Advice messages meet each sender's network conditions, if it has any
/// ([`Agent::link`]): a lost request reaches nobody, a lost reply or one
/// arriving after the asker's timeout is not counted by the asker.
#[derive(Debug)]
pub struct Team {
    agents: Vec<Agent>,
    actions: Vec<Action>,
    positions: Vec<[f64; 2]>,
    /// Episodes begun, training and evaluation alike.
    episodes: u32,
    /// Frames played in the current episode.
    frame: u32,
    /// Advising messages each agent sent.
    traffic: Vec<AdvisingTraffic>,
}

/// The advising messages an agent sent (advice requests, replies,
/// announcements, shared episodes, batches and reports of advice outcomes)
/// and their bytes, encoded as the zenoh transport sends them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AdvisingTraffic {
    /// Messages sent.
    pub messages: u64,
    /// Their encoded bytes.
    pub bytes: u64,
}

impl AdvisingTraffic {
    fn count(&mut self, header: Header, body: Body) {
        self.messages += 1;
        self.bytes += proto::encode(&Envelope { header, body }).len() as u64;
    }
}

impl Team {
    /// A team of agents whose ids are their indices.
    pub fn new(agents: Vec<Agent>) -> Result<Self, TeamError> {
        let size = agents.len();
        for (index, a) in agents.iter().enumerate() {
            if a.id() != index {
                return Err(TeamError::Id { index, id: a.id() });
            }
            if a.team_size() != size {
                return Err(TeamError::Size {
                    id: index,
                    built_for: a.team_size(),
                    size,
                });
            }
        }
        Ok(Self {
            actions: vec![Action::Move; size],
            positions: Vec::with_capacity(size),
            agents,
            episodes: 0,
            frame: 0,
            traffic: vec![AdvisingTraffic::default(); size],
        })
    }

    /// Puts `newcomer` in its id's slot between episodes, with its own
    /// traffic from zero; returns the agent that leaves.
    pub fn replace(&mut self, newcomer: Agent) -> Result<Agent, TeamError> {
        let (id, size) = (newcomer.id(), self.agents.len());
        if newcomer.team_size() != size {
            return Err(TeamError::Size {
                id,
                built_for: newcomer.team_size(),
                size,
            });
        }
        let slot = self
            .agents
            .get_mut(id)
            .ok_or(TeamError::Id { index: size, id })?;
        self.traffic[id] = AdvisingTraffic::default();
        let left = std::mem::replace(slot, newcomer);
        for a in &mut self.agents {
            a.peer_joined(id);
        }
        Ok(left)
    }

    /// The agents, by id.
    pub fn agents(&self) -> &[Agent] {
        &self.agents
    }

    /// The advising messages each agent sent so far, by id.
    pub fn traffic(&self) -> &[AdvisingTraffic] {
        &self.traffic
    }

    /// Starts an episode for every agent.
    pub fn begin_episode(&mut self, mode: Mode) {
        self.episodes += 1;
        self.frame = 0;
        for a in &mut self.agents {
            a.begin_episode(mode);
        }
    }

    /// One frame: every agent closes its previous step with the shared
    /// `reward` (ignored on the first frame) and picks its action.
    pub fn act(
        &mut self,
        observations: &[Observation],
        reward: f64,
    ) -> Result<&[Action], TeamError> {
        let n = self.agents.len();
        if observations.len() != n {
            return Err(TeamError::Observations {
                expected: n,
                got: observations.len(),
            });
        }
        self.positions.clear();
        self.positions
            .extend(observations.iter().map(|o| o.position));
        let (episode, frame) = (self.episodes.saturating_sub(1), self.frame);
        for (i, obs) in observations.iter().enumerate() {
            let (me, mut peers) = Peers::split(&mut self.agents, &mut self.traffic, i);
            peers.clock = (episode, frame);
            peers.link = me.link().copied();
            self.actions[i] = me.act(obs, reward, &self.positions, &mut peers);
            self.announce((episode, frame));
            self.report(i, (episode, frame));
        }
        self.frame += 1;
        Ok(&self.actions)
    }

    /// Delivers the announcements of the advisors whose give budget was
    /// just spent to every other agent, one message each.
    fn announce(&mut self, (episode, frame): (u32, u32)) {
        for j in 0..self.agents.len() {
            if !self.agents[j].take_announcement() {
                continue;
            }
            let header = Header::new(proto::experiment_id("in-process"), 0, episode, frame);
            let announcement = Body::Exhausted(Exhausted { from: j as u8 });
            self.traffic[j].count(header, announcement);
            for (k, a) in self.agents.iter_mut().enumerate() {
                if k != j {
                    a.hear_exhausted(j);
                }
            }
        }
    }

    /// Delivers agent `i`'s reports of advice outcomes to their advisors,
    /// one message each.
    fn report(&mut self, i: usize, (episode, frame): (u32, u32)) {
        for r in self.agents[i].take_reports() {
            let header = Header::new(proto::experiment_id("in-process"), 0, episode, frame);
            let report = Body::AdviceOutcome(AdviceOutcome {
                from: i as u8,
                to: r.advisor as u8,
                followed: r.followed,
                advantage: r.advantage,
            });
            self.traffic[i].count(header, report);
            if let Some(advisor) = self.agents.get_mut(r.advisor) {
                advisor.hear_advice_outcome(i, r.followed, r.advantage);
            }
        }
    }

    /// The terminal frame of an episode that ended with `outcome`: every
    /// agent learns its last step, then, in id order, the agents send their
    /// reports of advice outcomes and what they share.
    pub fn end_episode(&mut self, outcome: EpisodeOutcome) {
        for a in &mut self.agents {
            a.end_episode(outcome);
        }
        let episode = self.episodes.saturating_sub(1);
        for i in 0..self.agents.len() {
            self.report(i, (episode, self.frame));
        }
        for i in 0..self.agents.len() {
            let (me, mut peers) = Peers::split(&mut self.agents, &mut self.traffic, i);
            peers.clock = (episode, self.frame);
            me.share_episode(&mut peers);
        }
    }
}

/// Every agent but one, reachable by id, and that one's link at the
/// frame's (episode, frame).
struct Peers<'a> {
    before: &'a mut [Agent],
    after: &'a mut [Agent],
    me: usize,
    link: Option<Link>,
    clock: (u32, u32),
    traffic: &'a mut [AdvisingTraffic],
}

impl<'a> Peers<'a> {
    /// Agent `i` and the others.
    fn split(
        agents: &'a mut [Agent],
        traffic: &'a mut [AdvisingTraffic],
        i: usize,
    ) -> (&'a mut Agent, Self) {
        let (before, rest) = agents.split_at_mut(i);
        let (me, after) = rest.split_first_mut().expect("index below the team size");
        (
            me,
            Self {
                before,
                after,
                me: i,
                link: None,
                clock: (0, 0),
                traffic,
            },
        )
    }

    /// The message from `from` to `to` in this frame.
    fn message(&self, from: usize, to: usize, leg: Leg) -> Message {
        let (episode, frame) = self.clock;
        Message {
            episode,
            frame,
            from,
            to,
            leg,
        }
    }

    /// The header of this frame's messages, as the zenoh transport's of a
    /// run 0 of an experiment named `in-process`.
    fn header(&self) -> Header {
        let (episode, frame) = self.clock;
        Header::new(proto::experiment_id("in-process"), 0, episode, frame)
    }

    fn get(&mut self, id: usize) -> Option<&mut Agent> {
        match id.checked_sub(self.me) {
            None => self.before.get_mut(id),
            Some(0) => None,
            Some(d) => self.after.get_mut(d - 1),
        }
    }
}

impl AdviceExchange for Peers<'_> {
    fn ask(
        &mut self,
        from: usize,
        to: &[usize],
        state: &State,
        features: &Features,
        along: Along,
        answers: &mut Answers,
    ) -> u64 {
        let delay = |link: Option<&Link>, message| link.map_or(Some(0.0), |l| l.delay(message));
        let asker = self.link;
        let header = self.header();
        let request = AdviceRequest {
            from: from as u8,
            state: *state,
            along,
        };
        let request = match features.is_empty() {
            true => Body::AdviceRequest(request),
            false => Body::FeaturedRequest(FeaturedRequest {
                request,
                features: *features,
            }),
        };
        let mut replies = 0;
        for &j in to {
            self.traffic[from].count(header, request.clone());
            let Some(sent) = delay(asker.as_ref(), self.message(from, j, Leg::Request)) else {
                continue;
            };
            let back = self.message(j, from, Leg::Reply);
            let Some(advisor) = self.get(j) else {
                continue;
            };
            let answer = advisor.answer(from, state, features.as_slice(), along);
            let arrives = delay(advisor.link(), back)
                .is_some_and(|b| asker.is_none_or(|l| sent + b <= l.timeout_ms()));
            let from = j as u8;
            let reply = match answer {
                Answer::Action(answer) => Body::AdviceReply(AdviceReply { from, answer }),
                Answer::Values(answer) => Body::ValuesReply(ValuesReply { from, answer }),
            };
            self.traffic[j].count(header, reply);
            replies += u64::from(arrives);
            if arrives {
                answers.take(j, answer);
            }
        }
        replies
    }

    fn share(&mut self, from: usize, to: usize, share: &Share) {
        let (sender, receiver, transitions) = (from as u8, to as u8, share.transitions().to_vec());
        let body = match share {
            Share::Episode(_) => Body::SharedEpisode(SharedEpisode {
                from: sender,
                to: receiver,
                transitions,
            }),
            Share::Batch(batch) => Body::ExperienceBatch(ExperienceBatch {
                from: sender,
                to: receiver,
                transitions,
                notes: batch.notes.clone(),
                standing: batch.standing,
            }),
        };
        let header = self.header();
        self.traffic[from].count(header, body);
        if let Some(a) = self.get(to) {
            match share {
                Share::Episode(t) => a.receive_shared(t),
                Share::Batch(batch) => {
                    a.receive_batch(from, batch);
                }
            }
        }
    }
}
