use fluid_solver::probes;
use fluid_solver::{FluidSolver, Kind};
use schemas::case::fluid::{ProbeConfig, ProbeKind};
use schemas::case::Case;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ds: f64 = args[1].parse().unwrap();
    let dt: f64 = args[2].parse().unwrap();
    let t_end: f64 = args[3].parse().unwrap();
    let case = Case::load(std::path::Path::new("../cases/hydrostatic-tank/case.toml")).unwrap();
    let mut cfg = case.fluid.values().next().unwrap().clone();
    cfg.spacing = ds; cfg.tank.max = [0.2, 0.2, 0.4]; cfg.block[0].max = [0.2, 0.2, 0.3]; cfg.time_step = dt;
    if args.len() > 4 { cfg.viscosity_term = false; }
    cfg.validate("f").unwrap();
    let mut s = FluidSolver::new(&cfg);
    let tank = s.tank();
    let pr = |z: f64| ProbeConfig { name: "p".into(), kind: ProbeKind::Pressure, position: vec![0.1, 0.1, z], axis: None };
    let h = ProbeConfig { name: "h".into(), kind: ProbeKind::WaterHeight, position: vec![0.1, 0.1], axis: None };
    while s.time() < t_end {
        s.advance_to(s.time() + 0.05).unwrap();
        let p = s.particles();
        let ke: f64 = (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid.code()).map(|i| 0.5 * (p.vx[i].powi(2) + p.vy[i].powi(2) + p.vz[i].powi(2))).sum();
        let hh = probes::sample(&h, p, s.kernel(), &tank);
        let p1 = probes::sample(&pr(0.1), p, s.kernel(), &tank);
        println!("{:.2} ke {:.3e} h {:.4} p(0.1) {:.1} exact {:.1}", s.time(), ke, hh, p1, 9800.0 * (hh - 0.1));
    }
}
