//! Joining the network: every declaration of the agent, its tasks, and
//! leaving once stopped.

use std::sync::Arc;

use anyhow::{Result, anyhow};
use node::net::{NetConfig, describe};
use proto::keys::{Keys, Role};

use crate::child::ChildCommands;
use crate::context::{Context, Exit};
use crate::frames::Stream;
use crate::{advise, alive, control, frames, unique};

/// Who this agent is and how it joins the network.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Experiment name.
    pub name: String,
    /// The experiment's keys.
    pub keys: Keys,
    /// This agent's id.
    pub id: u8,
    /// Agents in the team.
    pub team_size: u8,
    /// zenoh endpoints.
    pub net: NetConfig,
    /// Exit once the coordinator that was seen is gone.
    pub exit_with_coordinator: bool,
    /// Its learner and strategy processes, where given.
    pub children: ChildCommands,
}

/// Joins the network, serves until stopped, and leaves it.
pub async fn run(settings: Settings) -> Result<Exit> {
    let Settings {
        name,
        keys,
        id,
        team_size,
        net,
        exit_with_coordinator,
        children,
    } = settings;
    let session = node::net::open(&net).await?;
    unique::ensure_unique(&session, &keys, &name, id).await?;
    let declare = |what: &str, e: zenoh::Error| anyhow!("cannot declare {what}: {}", describe(&e));
    let tokens = session
        .liveliness()
        .declare_subscriber(keys.alive_all())
        .history(true)
        .await
        .map_err(|e| declare("the liveliness subscriber", e))?;
    let actions = session
        .declare_publisher(keys.action(id))
        .await
        .map_err(|e| declare("the action publisher", e))?;
    let ctx = Arc::new(Context::new(
        session.clone(),
        &name,
        keys,
        (id, team_size),
        children,
    ));
    let (stream, tasks) = Stream::new(ctx.clone(), actions);
    // Held until the end: dropping them undeclares them.
    let _observations = {
        let stream = stream.clone();
        session
            .declare_subscriber(ctx.keys.observation(id))
            .callback(move |s| stream.on_message(&s.payload().to_bytes()))
            .await
            .map_err(|e| declare("the observation subscriber", e))?
    };
    let _shares = {
        let ctx = ctx.clone();
        session
            .declare_subscriber(ctx.keys.share(id))
            .callback(move |s| frames::on_share(&ctx, &s.payload().to_bytes()))
            .await
            .map_err(|e| declare("the share subscriber", e))?
    };
    let _exhausted = {
        let ctx = ctx.clone();
        session
            .declare_subscriber(ctx.keys.exhausted_all())
            .callback(move |s| advise::on_exhausted(&ctx, &s.payload().to_bytes()))
            .await
            .map_err(|e| declare("the announcement subscriber", e))?
    };
    let _advice = {
        let ctx = ctx.clone();
        let runtime = tokio::runtime::Handle::current();
        session
            .declare_queryable(ctx.keys.advice(id))
            .callback(move |q| advise::answer(&ctx, q, &runtime))
            .await
            .map_err(|e| declare("the advice queryable", e))?
    };
    let control = session
        .declare_queryable(ctx.keys.control(Role::Agent(id)))
        .await
        .map_err(|e| declare("the control queryable", e))?;
    tokio::spawn(alive::track(ctx.clone(), tokens, exit_with_coordinator));
    tokio::spawn(frames::run(stream, tasks));
    tokio::spawn(control::serve(ctx.clone(), control));
    // Declared last: whoever sees the token can already reach the rest.
    let token = session
        .liveliness()
        .declare_token(ctx.keys.alive(Role::Agent(id)))
        .await
        .map_err(|e| declare("the liveliness token", e))?;
    tracing::info!(experiment = %name, id, "agent ready");
    let exit = ctx.stopped().await;
    tracing::info!(?exit, "stopping");
    drop(token);
    session
        .close()
        .await
        .map_err(|e| anyhow!("cannot leave the zenoh network cleanly: {}", describe(&e)))?;
    Ok(exit)
}
