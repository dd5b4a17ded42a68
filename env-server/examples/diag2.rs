use env_server::*;
use env_server::physics::Command;
use env_server::rollout::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let policy: BaselinePolicy = args[1].parse().unwrap();
    let mut cfg = EnvConfig::default(); cfg.long_shot.speed = 2.0; cfg.long_shot.min_speed = 1.5;
    let mut env = Env::new(cfg, 7).unwrap();
    let mut rng = policy_rng(7);
    let mut shown = 0;
    for ep in 0..3000 {
        let mut last_kick = None;
        let mut traj = Vec::new();
        let (o, f) = play_episode(&mut env, policy, &mut rng, |env| {
            let w = env.world();
            let n = env.offense();
            if env.last_commands()[..n].iter().any(|c| matches!(c, Command::Kick{..})) {
                last_kick = Some((env.frame(), w.ball.pos, w.ball.vel.length() / 0.94, w.keeper.pos));
            }
            traj.push((env.frame(), w.ball.pos, w.ball.vel, w.keeper.pos, w.keeper.body.to_degrees(), env.last_commands()[n]));
        });
        if o == Outcome::Goal && shown < 6 && last_kick.unwrap().1.x < 36.0 {
            shown += 1;
            let (kf, b, v, k) = last_kick.unwrap();
            println!("ep {ep} goal at {f}: last kick frame {kf} ball ({:.1},{:.1}) speed {:.2} keeper ({:.1},{:.1})", b.x, b.y, v, k.x, k.y);
            if shown <= 1 { for t in traj.iter().filter(|t| t.0 + 1 >= kf) { println!("   {:?}", t); } }
        }
    }
}
