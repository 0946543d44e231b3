use spherecontact::fem::FemAxisym;
use spherecontact::pair::{Body, ContactPair, Material};
use spherecontact::path::{LoadingPath, Position};
use spherecontact::scene::Scene;
use spherecontact::solver::run;
fn fit(x: &[f64], y: &[f64]) -> f64 { // zero of LS line
    let n = x.len() as f64; let sx: f64 = x.iter().sum(); let sy: f64 = y.iter().sum();
    let sxx: f64 = x.iter().map(|v| v*v).sum(); let sxy: f64 = x.iter().zip(y).map(|(a,b)| a*b).sum();
    let b = (n*sxy - sx*sy)/(n*sxx - sx*sx); let a = (sy - b*sx)/n; -a/b }
fn fit3(x: &[f64], y: &[f64]) -> f64 {
    let x0 = x[x.len()-1];
    let mut m = [[0.0f64;3];3]; let mut r = [0.0f64;3];
    for (a,b) in x.iter().zip(y) { let t = a - x0; let bs = [1.0, t, t*t]; for i in 0..3 { r[i]+=bs[i]*b; for j in 0..3 { m[i][j]+=bs[i]*bs[j]; } } }
    // solve 3x3 by Cramer
    let det = |m: [[f64;3];3]| m[0][0]*(m[1][1]*m[2][2]-m[1][2]*m[2][1]) - m[0][1]*(m[1][0]*m[2][2]-m[1][2]*m[2][0]) + m[0][2]*(m[1][0]*m[2][1]-m[1][1]*m[2][0]);
    let d = det(m); let mut c = [0.0;3];
    for k in 0..3 { let mut mk = m; for i in 0..3 { mk[i][k] = r[i]; } c[k] = det(mk)/d; }
    // root of c0 + c1 t + c2 t^2 near t=0+
    let disc = c[1]*c[1] - 4.0*c[0]*c[2];
    let t = if c[2].abs() < 1e-30 { -c[0]/c[1] } else { let s = disc.max(0.0).sqrt(); let t1 = (-c[1]+s)/(2.0*c[2]); let t2 = (-c[1]-s)/(2.0*c[2]); if (t1 - 0.0).abs() < (t2-0.0).abs() { t1 } else { t2 } };
    x0 + t
}
fn main() {
    for h in [50.0, 25.0, 12.5] {
    for d in [5.0, 10.0, 20.0] {
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
    for k in [8usize, 12, 16] {
        let s = &pts[n-k..n];
        let x: Vec<f64> = s.iter().map(|v| v.0).collect(); let y: Vec<f64> = s.iter().map(|v| v.1*v.1).collect();
        out.push(fit(&x, &y));
        out.push(fit3(&x, &y));
    }
    println!("h {h} d {d}: {}", out.iter().map(|o| format!("{:+.3}", 100.0*(o-1.0))).collect::<Vec<_>>().join(" "));
    }}
}
