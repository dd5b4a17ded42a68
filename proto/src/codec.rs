//! Encoding and checked decoding of [`Envelope`]s, and of the settings a
//! `Control::Reset` carries.

use crate::message::{Body, Envelope, Header, PROTOCOL_VERSION};
use crate::traffic::{DropReason, MessageCounters};
use serde::Serialize;
use serde::de::DeserializeOwned;
use thiserror::Error;

/// Why received bytes were not accepted as a message of this experiment.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum DecodeError {
    /// Not a message of this protocol at all.
    #[error("malformed message: {0}")]
    Malformed(String),
    /// A message of another protocol version.
    #[error("protocol version {found}, expected {expected}")]
    Version {
        /// Version in the message.
        found: u16,
        /// Our version.
        expected: u16,
    },
    /// A message of another experiment.
    #[error("message of experiment {0:#018x}")]
    Foreign(u64),
}

/// Encodes a message.
pub fn encode(envelope: &Envelope) -> Vec<u8> {
    // Every message type is plain data: serialising into a Vec cannot fail.
    postcard::to_allocvec(envelope).unwrap_or_default()
}

/// Decodes a message of `experiment`, checking version and experiment first
/// and then what a body may hold (an experience batch's bound, finite
/// numbers where a learner takes them); never panics, whatever the bytes.
pub fn decode(bytes: &[u8], experiment: u64) -> Result<Envelope, DecodeError> {
    let (header, _) = postcard::take_from_bytes::<Header>(bytes)
        .map_err(|e| DecodeError::Malformed(e.to_string()))?;
    if header.version != PROTOCOL_VERSION {
        return Err(DecodeError::Version {
            found: header.version,
            expected: PROTOCOL_VERSION,
        });
    }
    if header.experiment != experiment {
        return Err(DecodeError::Foreign(header.experiment));
    }
    let (envelope, rest) = postcard::take_from_bytes::<Envelope>(bytes)
        .map_err(|e| DecodeError::Malformed(e.to_string()))?;
    if !rest.is_empty() {
        return Err(DecodeError::Malformed(format!(
            "{} trailing bytes",
            rest.len()
        )));
    }
    check(&envelope.body).map_err(DecodeError::Malformed)?;
    Ok(envelope)
}

/// Why a decoded body cannot be taken, if it cannot.
fn check(body: &Body) -> Result<(), String> {
    match body {
        Body::ExperienceBatch(b) => b.check(),
        Body::AdviceOutcome(o) if !o.advantage.is_finite() => {
            Err(format!("an advice outcome of advantage {}", o.advantage))
        }
        _ => Ok(()),
    }
}

/// Settings that could not be encoded, or bytes that are not the settings
/// expected.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[error("{0}")]
pub struct SettingsError(String);

/// A process's settings (any serde type) as `Control::Reset` carries them:
/// their postcard encoding.
pub fn encode_settings<T: Serialize>(settings: &T) -> Result<Vec<u8>, SettingsError> {
    postcard::to_allocvec(settings).map_err(|e| SettingsError(e.to_string()))
}

/// The answer to a command of `experiment` that came in another protocol
/// version: a [`ControlReply::Error`](crate::ControlReply::Error) in this
/// version naming both, so the sender can say why this process will not
/// take part. `None` for bytes that are not such a command.
pub fn version_refusal(bytes: &[u8], experiment: u64) -> Option<Envelope> {
    let (header, _) = postcard::take_from_bytes::<Header>(bytes).ok()?;
    if header.version == PROTOCOL_VERSION || header.experiment != experiment {
        return None;
    }
    let reason = format!(
        "this process speaks protocol version {PROTOCOL_VERSION}, the command came in version {}: \
         every process of an experiment must run the same build",
        header.version
    );
    Some(Envelope {
        header: Header {
            version: PROTOCOL_VERSION,
            ..header
        },
        body: crate::Body::ControlReply(crate::ControlReply::Error(reason)),
    })
}

/// Decodes settings sent with `Control::Reset`; every byte must be used.
/// Checking the values is the caller's job.
pub fn decode_settings<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, SettingsError> {
    let (settings, rest) =
        postcard::take_from_bytes(bytes).map_err(|e| SettingsError(e.to_string()))?;
    if !rest.is_empty() {
        return Err(SettingsError(format!("{} trailing bytes", rest.len())));
    }
    Ok(settings)
}

impl MessageCounters {
    /// Counts a decode failure under its reason.
    pub fn drop_undecodable(&mut self, error: &DecodeError) {
        self.record_drop(match error {
            DecodeError::Malformed(_) => DropReason::Malformed,
            DecodeError::Version { .. } => DropReason::Version,
            DecodeError::Foreign(_) => DropReason::Foreign,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::*;
    use proptest::prelude::*;

    fn action() -> impl Strategy<Value = Action> {
        prop::sample::select(Action::ALL.to_vec())
    }

    fn state() -> impl Strategy<Value = State> {
        prop::array::uniform6(-1.0f64..=1.0)
    }

    fn features() -> impl Strategy<Value = Features> {
        prop::collection::vec(-1.0f32..=11.0, 0..=MAX_FEATURES)
            .prop_map(|v| Features::new(&v).expect("at most MAX_FEATURES"))
    }

    fn outcome() -> impl Strategy<Value = EpisodeOutcome> {
        prop::sample::select(vec![
            EpisodeOutcome::Goal,
            EpisodeOutcome::Captured,
            EpisodeOutcome::OutOfBounds,
            EpisodeOutcome::OutOfTime,
        ])
    }

    fn transitions(max: usize) -> impl Strategy<Value = Vec<SharedTransition>> {
        prop::collection::vec(
            (
                state(),
                action(),
                -1.0f64..=1.0,
                prop::option::of((state(), action())),
            )
                .prop_map(|(state, action, reward, next)| SharedTransition {
                    state,
                    action,
                    reward,
                    next,
                }),
            0..max,
        )
    }

    fn mode() -> impl Strategy<Value = Mode> {
        prop::sample::select(vec![Mode::Training, Mode::Evaluation])
    }

    /// Any message body: one `prop_oneof!` arm per kind, each over all its
    /// fields (long because the macro takes the arms as one expression).
    fn body() -> impl Strategy<Value = Body> {
        prop_oneof![
            prop::collection::vec(
                (
                    any::<u8>(),
                    mode(),
                    state(),
                    any::<bool>(),
                    prop::collection::vec(prop::array::uniform2(-60.0f64..60.0), 0..5),
                    -1.0f64..=1.0,
                    prop::option::of(outcome()),
                    features(),
                )
                    .prop_map(
                        |(agent, mode, state, can_kick, positions, reward, outcome, features)| {
                            AgentFrame {
                                agent,
                                mode,
                                state,
                                features,
                                can_kick,
                                positions,
                                reward,
                                outcome,
                            }
                        }
                    ),
                1..4
            )
            .prop_map(Body::Observations),
            (any::<u8>(), action())
                .prop_map(|(agent, action)| Body::Action(ActionChoice { agent, action })),
            (
                any::<u8>(),
                state(),
                prop_oneof![
                    Just(Along::Nothing),
                    action().prop_map(Along::Intended),
                    prop::array::uniform5(any::<u32>()).prop_map(Along::ActionVisits),
                ]
            )
                .prop_map(|(from, state, along)| Body::AdviceRequest(AdviceRequest {
                    from,
                    state,
                    along
                })),
            (any::<u8>(), state(), features()).prop_map(|(from, state, features)| {
                let request = AdviceRequest {
                    from,
                    state,
                    along: Along::Nothing,
                };
                Body::FeaturedRequest(FeaturedRequest { request, features })
            }),
            (
                any::<u8>(),
                prop::option::of(action()),
                0u8..3,
                -1e3f32..1e3
            )
                .prop_map(|(from, advice, kind, value)| Body::AdviceReply(
                    AdviceReply {
                        from,
                        answer: match (advice, kind) {
                            (Some(a), 0) => AdviceAnswer::Advice(a),
                            (Some(a), _) => AdviceAnswer::Recommendation(a, value),
                            (None, 0) => AdviceAnswer::Declined,
                            (None, _) => AdviceAnswer::Exhausted,
                        },
                    }
                )),
            any::<u8>().prop_map(|from| Body::Exhausted(Exhausted { from })),
            (any::<u8>(), any::<u8>(), transitions(20)).prop_map(|(from, to, transitions)| {
                Body::SharedEpisode(SharedEpisode {
                    from,
                    to,
                    transitions,
                })
            }),
            (
                any::<u8>(),
                any::<u8>(),
                transitions(20),
                any::<bool>(),
                prop::option::of((any::<u64>(), prop::option::of(0.0f64..1.0), -10.0f64..10.0)),
            )
                .prop_map(|(from, to, transitions, noted, standing)| {
                    let notes = (transitions.iter().enumerate())
                        .filter(|_| noted)
                        .map(|(k, _)| TransitionNote {
                            frames: k as u32 + 1,
                            uncertainty: k as f64 / 8.0,
                        })
                        .collect();
                    let standing = standing.map(|(episodes, uncertainty, mean_return)| Standing {
                        episodes,
                        uncertainty,
                        mean_return,
                    });
                    Body::ExperienceBatch(ExperienceBatch {
                        from,
                        to,
                        transitions,
                        notes,
                        standing,
                    })
                }),
            (any::<u8>(), any::<u8>(), any::<bool>(), -10.0f64..10.0).prop_map(
                |(from, to, followed, advantage)| Body::AdviceOutcome(AdviceOutcome {
                    from,
                    to,
                    followed,
                    advantage,
                })
            ),
            (any::<u64>(), prop::collection::vec(any::<u8>(), 0..40)).prop_map(|(seed, config)| {
                Body::Control(Control::Reset {
                    seed,
                    config,
                    wait_ms: seed % 1000,
                    stall_ms: seed % 7919,
                    simulator: if seed % 2 == 0 {
                        Simulator::Ours
                    } else {
                        Simulator::RealHfo
                    },
                    features: (seed % 16) as u8,
                })
            }),
            (
                any::<u32>(),
                any::<u32>(),
                prop::collection::vec(any::<u8>(), 0..100)
            )
                .prop_map(|(part, parts, bytes)| Body::Control(Control::Load {
                    part,
                    parts,
                    bytes
                })),
            (mode(), prop::option::of(any::<u64>()))
                .prop_map(|(mode, seed)| Body::Control(Control::PlayEpisode { mode, seed })),
            Just(Body::Control(Control::Report)),
            any::<u32>().prop_map(|part| Body::Control(Control::Snapshot { part })),
            Just(Body::Control(Control::Stop)),
            (any::<u32>(), prop::collection::vec(any::<u8>(), 0..100)).prop_map(
                |(parts, bytes)| Body::ControlReply(ControlReply::Snapshot { parts, bytes })
            ),
            (any::<u32>()).prop_map(|frames| Body::ControlReply(ControlReply::Episode(
                EpisodeResult {
                    outcome: EpisodeOutcome::Goal,
                    frames,
                    actions_timed_out: frames / 3,
                }
            ))),
            (any::<u64>(), prop::collection::vec(0f32..100.0, 0..10)).prop_map(
                |(digest, advice_rtt_ms)| Body::ControlReply(ControlReply::Agent(Box::new(
                    AgentReport {
                        digest,
                        advice_rtt_ms,
                        ..AgentReport::default()
                    }
                )))
            ),
            ".{0,40}".prop_map(|e| Body::ControlReply(ControlReply::Error(e))),
            ".{0,40}".prop_map(|e| Body::ControlReply(ControlReply::SimulatorFailed(e))),
            (
                any::<u8>(),
                prop::option::of((prop::array::uniform5(-10.0f64..10.0), 0u8..32, any::<u64>())),
                action(),
            )
                .prop_map(|(from, values, best)| Body::ValuesReply(ValuesReply {
                    from,
                    answer: match values {
                        Some((q, learned, visits)) if learned % 2 == 0 => {
                            ValuesAnswer::Values(SharedValues { q, learned, visits })
                        }
                        Some((q, ..)) => ValuesAnswer::Best(best, q[0]),
                        None => ValuesAnswer::Declined,
                    },
                })),
        ]
    }

    fn header(experiment: u64) -> impl Strategy<Value = Header> {
        (any::<u32>(), any::<u32>(), any::<u32>())
            .prop_map(move |(run, episode, frame)| Header::new(experiment, run, episode, frame))
    }

    proptest! {
        #[test]
        fn round_trips(header in header(7), body in body()) {
            let envelope = Envelope { header, body };
            prop_assert_eq!(decode(&encode(&envelope), 7), Ok(envelope));
        }

        #[test]
        fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
            let _ = decode(&bytes, 7);
        }

        #[test]
        fn truncated_messages_are_malformed(header in header(7), body in body(), cut in 0usize..1000) {
            let bytes = encode(&Envelope { header, body });
            let cut = cut % bytes.len();
            prop_assert!(decode(&bytes[..cut], 7).is_err());
        }
    }

    #[test]
    fn settings_round_trip_and_leftovers_are_refused() {
        #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
        struct Example {
            rate: f64,
            name: String,
        }
        let settings = Example {
            rate: 0.5,
            name: "x".into(),
        };
        let mut bytes = encode_settings(&settings).unwrap();
        assert_eq!(decode_settings::<Example>(&bytes), Ok(settings));
        assert!(decode_settings::<Example>(&bytes[..bytes.len() - 1]).is_err());
        bytes.push(0);
        let e = decode_settings::<Example>(&bytes).unwrap_err();
        assert_eq!(e.to_string(), "1 trailing bytes");
    }

    #[test]
    fn foreign_and_old_messages_are_recognised() {
        let envelope = Envelope {
            header: Header::new(1, 0, 0, 0),
            body: Body::Control(Control::Stop),
        };
        assert_eq!(decode(&encode(&envelope), 2), Err(DecodeError::Foreign(1)));
        let old = Envelope {
            header: Header {
                version: PROTOCOL_VERSION + 1,
                ..envelope.header
            },
            ..envelope
        };
        assert!(matches!(
            decode(&encode(&old), 1),
            Err(DecodeError::Version { .. })
        ));
        let mut bytes = encode(&Envelope {
            header: Header::new(1, 0, 0, 0),
            body: Body::Control(Control::Stop),
        });
        bytes.push(0);
        assert!(matches!(decode(&bytes, 1), Err(DecodeError::Malformed(_))));
    }

    #[test]
    fn oversized_or_unfinite_batches_and_outcomes_are_malformed() {
        let t = SharedTransition {
            state: [0.5; 6],
            action: Action::Shoot,
            reward: 1.0,
            next: Some(([0.25; 6], Action::Move)),
        };
        let batch = |transitions: Vec<SharedTransition>| {
            encode(&Envelope {
                header: Header::new(1, 0, 0, 0),
                body: Body::ExperienceBatch(ExperienceBatch {
                    from: 0,
                    to: 1,
                    transitions,
                    notes: Vec::new(),
                    standing: None,
                }),
            })
        };
        assert!(decode(&batch(vec![t; MAX_BATCH]), 1).is_ok());
        let long = decode(&batch(vec![t; MAX_BATCH + 1]), 1);
        assert!(matches!(long, Err(DecodeError::Malformed(e)) if e.contains("4097 transitions")));
        let nan = SharedTransition {
            next: Some(([f64::NAN; 6], Action::Move)),
            ..t
        };
        assert!(matches!(
            decode(&batch(vec![t, nan]), 1),
            Err(DecodeError::Malformed(_))
        ));
        let outcome = |advantage| {
            encode(&Envelope {
                header: Header::new(1, 0, 0, 0),
                body: Body::AdviceOutcome(AdviceOutcome {
                    from: 1,
                    to: 0,
                    followed: true,
                    advantage,
                }),
            })
        };
        assert!(decode(&outcome(-0.5), 1).is_ok());
        assert!(matches!(
            decode(&outcome(f64::INFINITY), 1),
            Err(DecodeError::Malformed(_))
        ));
    }

    /// A batch of `n` transitions with `notes` and `standing`, encoded
    /// under protocol `version`.
    fn noted(n: usize, notes: Vec<TransitionNote>, standing: Option<Standing>) -> Vec<u8> {
        let t = SharedTransition {
            state: [0.5; 6],
            action: Action::Dribble,
            reward: 0.25,
            next: Some(([0.25; 6], Action::Shoot)),
        };
        encode(&Envelope {
            header: Header::new(1, 0, 0, 0),
            body: Body::ExperienceBatch(ExperienceBatch {
                from: 2,
                to: 0,
                transitions: vec![t; n],
                notes,
                standing,
            }),
        })
    }

    #[test]
    fn a_batch_s_notes_are_one_per_transition_or_none_and_finite() {
        let note = |frames, uncertainty| TransitionNote {
            frames,
            uncertainty,
        };
        let standing = |uncertainty, mean_return| Standing {
            episodes: 100,
            uncertainty,
            mean_return,
        };
        let malformed = |bytes: Vec<u8>, says: &str| match decode(&bytes, 1) {
            Err(DecodeError::Malformed(e)) => assert!(e.contains(says), "{e}"),
            other => panic!("{other:?}"),
        };
        let fine = standing(Some(0.5), -0.25);
        let ok = decode(&noted(3, vec![note(2, 0.5); 3], Some(fine)), 1).unwrap();
        let Body::ExperienceBatch(b) = ok.body else {
            panic!("{ok:?}")
        };
        assert_eq!((b.notes.len(), b.standing), (3, Some(fine)));
        // None at all, or a standing alone (no transition), are fine too.
        assert!(decode(&noted(3, Vec::new(), None), 1).is_ok());
        assert!(decode(&noted(0, Vec::new(), Some(standing(None, 0.0))), 1).is_ok());
        // Neither one per transition nor none.
        malformed(
            noted(3, vec![note(2, 0.5); 2], None),
            "3 transitions with 2 notes",
        );
        malformed(
            noted(1, vec![note(2, 0.5); 2], None),
            "1 transitions with 2 notes",
        );
        malformed(
            noted(0, vec![note(2, 0.5)], None),
            "0 transitions with 1 notes",
        );
        // Numbers that are not finite, a note of no frame, too many frames.
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            malformed(
                noted(2, vec![note(1, 0.5), note(1, bad)], None),
                "not finite",
            );
            malformed(
                noted(2, Vec::new(), Some(standing(Some(bad), 0.0))),
                "not finite",
            );
            malformed(
                noted(2, Vec::new(), Some(standing(None, bad))),
                "not finite",
            );
        }
        malformed(noted(2, vec![note(1, 0.5), note(0, 0.5)], None), "no frame");
        let most = (MAX_BATCH_FRAMES / 2) as u32;
        assert!(decode(&noted(2, vec![note(most, 0.5); 2], None), 1).is_ok());
        let over = vec![note(most, 0.5), note(most + 1, 0.5)];
        malformed(noted(2, over, None), "more than 262144");
        let longest = vec![note(u32::MAX, 0.5); 4];
        malformed(noted(4, longest, None), "frames, more than");
    }

    #[test]
    fn a_batch_from_an_older_peer_is_refused_by_its_version() {
        let mut bytes = noted(2, Vec::new(), None);
        // The header comes first: a version 12 sender (no notes, no
        // standing) is refused before its body is read.
        let old = postcard::to_allocvec(&Header {
            version: 12,
            ..Header::new(1, 0, 0, 0)
        })
        .unwrap();
        let new = postcard::to_allocvec(&Header::new(1, 0, 0, 0)).unwrap();
        assert_eq!(bytes[..new.len()], new[..]);
        bytes.splice(..new.len(), old);
        assert_eq!(
            decode(&bytes, 1),
            Err(DecodeError::Version {
                found: 12,
                expected: 13
            })
        );
    }

    #[test]
    fn answers_are_encoded_as_the_options_they_replace() {
        let old = |a: Option<Action>| postcard::to_allocvec(&a).unwrap();
        let new = |a: AdviceAnswer| postcard::to_allocvec(&a).unwrap();
        assert_eq!(new(AdviceAnswer::Declined), old(None));
        assert_eq!(
            new(AdviceAnswer::Advice(Action::Shoot)),
            old(Some(Action::Shoot))
        );
        assert_eq!(new(AdviceAnswer::Exhausted).len(), 1);
        let values = SharedValues {
            q: [0.5; 5],
            learned: 3,
            visits: 9,
        };
        let old = postcard::to_allocvec(&Some(values)).unwrap();
        let new = postcard::to_allocvec(&ValuesAnswer::Values(values)).unwrap();
        assert_eq!(new, old);
        let old = |a: Option<Action>| postcard::to_allocvec(&a).unwrap();
        let new = |a: Along| postcard::to_allocvec(&a).unwrap();
        assert_eq!(new(Along::Nothing), old(None));
        assert_eq!(
            new(Along::Intended(Action::Dribble)),
            old(Some(Action::Dribble))
        );
    }
}
