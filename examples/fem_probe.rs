use spherecontact::fem::FemAxisym;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::run;
fn main() {
    let h: f64 = std::env::args().nth(1).unwrap().parse().unwrap();
    let d: f64 = std::env::args().nth(2).unwrap_or("17".into()).parse().unwrap();
    let b = Body { radius: 0.1, material: Material { young: 70e9, poisson: 0.3 } };
    let scene = Scene { name: "p".into(), pair: ContactPair { body1: b, body2: b }, friction: 0.2,
        path: LoadingPath::try_new(vec![Position{delta_n:0.0,delta_t:0.0}, Position{delta_n:d*1e-6,delta_t:0.0}], vec![1]).unwrap() };
    let hz = scene.hertz();
    let hist = run(&FemAxisym::with_pole_size(h*1e-6), &scene).unwrap();
    let row = &hist.steps[1];
    let dn = d*1e-6;
    println!("P {:+.4}% c {:+.4}% p0 {:+.4}%  wall {:.3}", 100.0*(row.normal_force.unwrap()/hz.force(dn)-1.0),
      100.0*(row.contact_radius.unwrap()/hz.contact_radius(dn)-1.0), 100.0*(row.peak_pressure.unwrap()/hz.peak_pressure(dn)-1.0), hist.metadata.wall_time_s);
    println!("{:?}", hist.metadata.extra);
    println!("{:?}", hist.metadata.warnings);
}
