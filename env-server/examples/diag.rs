use env_server::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let policy: BaselinePolicy = args[1].parse().unwrap();
    let speed: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(3.0);
    let min: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(2.0);
    let sigma: f64 = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(10.0);
    let mut cfg = EnvConfig::default();
    cfg.long_shot.speed = speed; cfg.long_shot.min_speed = min; cfg.long_shot.sigma_deg = sigma;
    let s = rollout(cfg, policy, 4000, 7).unwrap();
    println!("{speed} {min} {sigma}: goal {:.2}% frames {:.1} tg {:.1} cap {} oob {} oot {}", s.goal_pct, s.mean_frames, s.mean_frames_to_goal, s.outcomes.captured, s.outcomes.out_of_bounds, s.outcomes.out_of_time);
}
