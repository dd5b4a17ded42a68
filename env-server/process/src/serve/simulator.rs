//! What a served run's episodes are played on: the frames the server needs
//! from a simulator, whichever it is: ours (`env_server::Env`) or the real
//! HFO behind a pipe ([`super::real_hfo`]).

use env_server::{Env, Outcome};
use proto::{Action, Features, State};

/// A simulator as the server steps it. Ours cannot fail; the real HFO, a
/// child process, can, and says why in one line.
pub trait ServedSimulator {
    /// Number of offense agents.
    fn offense(&self) -> usize;
    /// Begins an episode.
    fn reset(&mut self) -> Result<(), String>;
    /// Steps with every agent's action (Move for those that cannot kick).
    fn step(&mut self, actions: &[Action]) -> Result<Outcome, String>;
    /// The frame within the episode.
    fn frame(&self) -> u32;
    /// Whether `agent` can kick this frame.
    fn can_kick(&self, agent: usize) -> bool;
    /// The paper's state of `agent` this frame.
    fn state(&self, agent: usize) -> State;
    /// HFO's features of `agent` this frame (today's set, docs/python.md
    /// "The `hfo` set"); none where the simulator gives the paper's state
    /// only.
    fn features(&self, agent: usize) -> Option<Features>;
    /// Every offense agent's field position (m), by id.
    fn positions(&self) -> Vec<[f64; 2]>;
}

impl ServedSimulator for Env {
    fn offense(&self) -> usize {
        Env::offense(self)
    }

    fn reset(&mut self) -> Result<(), String> {
        Env::reset(self);
        Ok(())
    }

    fn step(&mut self, actions: &[Action]) -> Result<Outcome, String> {
        Ok(Env::step(self, actions))
    }

    fn frame(&self) -> u32 {
        Env::frame(self)
    }

    fn can_kick(&self, agent: usize) -> bool {
        Env::can_kick(self, agent)
    }

    fn state(&self, agent: usize) -> State {
        Env::state(self, agent)
    }

    fn features(&self, agent: usize) -> Option<Features> {
        Features::from_f64(&self.current_features(agent))
    }

    fn positions(&self) -> Vec<[f64; 2]> {
        self.world()
            .offense
            .iter()
            .map(|p| [p.pos.x, p.pos.y])
            .collect()
    }
}
