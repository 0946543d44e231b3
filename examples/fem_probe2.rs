use spherecontact::fem::FemAxisym;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::run;
fn fit(x: &[f64], y: &[f64]) -> f64 { // zero of LS line
    let n = x.len() as f64; let sx: f64 = x.iter().sum(); let sy: f64 = y.iter().sum();
    let sxx: f64 = x.iter().map(|v| v*v).sum(); let sxy: f64 = x.iter().zip(y).map(|(a,b)| a*b).sum();
    let b = (n*sxy - sx*sy)/(n*sxx - sx*sx); let a = (sy - b*sx)/n; -a/b }
fn main() {
    for h in [50.0, 25.0, 12.5] {
    for d in [5.0, 10.0, 17.0, 20.0] {
    let b = Body { radius: 0.1, material: Material { young: 70e9, poisson: 0.3 } };
    let scene = Scene { name: "p".into(), pair: ContactPair { body1: b, body2: b }, friction: 0.2,
        path: LoadingPath::try_new(vec![Position{delta_n:0.0,delta_t:0.0}, Position{delta_n:d*1e-6,delta_t:0.0}], vec![1]).unwrap() };
    let hz = scene.hertz();
    let hist = run(&FemAxisym::with_pole_size(h*1e-6), &scene).unwrap();
    let f = &hist.fields[1];
    let p = hist.steps[1].normal_force.unwrap();
    let c = (3.0*p*hz.effective_radius/(4.0*hz.effective_modulus)).cbrt();
    let pts: Vec<(f64,f64)> = f.points.iter().zip(&f.pressure).filter(|(_, p)| **p > 0.0).map(|(x,p)| (x[0]/c, *p)).collect();
    let n = pts.len();
    let mut out = vec![hist.steps[1].contact_radius.unwrap()/c];
    for k in [3usize, 5, 8, 12] {
        for skip in [0usize, 1] {
        let s = &pts[n-k-skip..n-skip];
        let x: Vec<f64> = s.iter().map(|v| v.0).collect(); let y: Vec<f64> = s.iter().map(|v| v.1*v.1).collect();
        out.push(fit(&x, &y));
        let x2: Vec<f64> = x.iter().map(|v| v*v).collect(); out.push(fit(&x2,&y).sqrt());
    }}
    println!("h {h} d {d}: {}", out.iter().map(|o| format!("{:+.3}", 100.0*(o-1.0))).collect::<Vec<_>>().join(" "));
    }}
}
