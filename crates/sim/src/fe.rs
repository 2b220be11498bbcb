//! Finite elements: cubic Hermite for q (nodal q, q'), linear Lagrange for θ, consistent
//! coupled mass, on N uniform elements. Element integrals by 4-point Gauss–Legendre
//! quadrature, exact for the polynomial degrees involved (≤ 7). Unknown ordering per node
//! i = 1..N: (q_i, q'_i, θ_i) at 3(i−1)+{0,1,2}; the clamp removes node 0.

use wingcheck_model::Config;

use crate::assembly::{builders, finish, initial_q, initial_theta, output_grid, Interpolation, RawAssembly};
use crate::strain::StrainRow;

/// 4-point Gauss–Legendre nodes and weights on [0, 1].
const GAUSS: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_87, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// Hermite shape functions on an element of length h at local coordinate u ∈ [0,1]:
/// values, first and second z-derivatives for the DOFs (w(0), w'(0), w(h), w'(h)).
pub fn hermite(u: f64, h: f64) -> ([f64; 4], [f64; 4], [f64; 4]) {
    let n = [
        1.0 - 3.0 * u * u + 2.0 * u.powi(3),
        h * (u - 2.0 * u * u + u.powi(3)),
        3.0 * u * u - 2.0 * u.powi(3),
        h * (-u * u + u.powi(3)),
    ];
    let d = [
        (-6.0 * u + 6.0 * u * u) / h,
        1.0 - 4.0 * u + 3.0 * u * u,
        (6.0 * u - 6.0 * u * u) / h,
        -2.0 * u + 3.0 * u * u,
    ];
    let dd = [(-6.0 + 12.0 * u) / (h * h), (-4.0 + 6.0 * u) / h, (6.0 - 12.0 * u) / (h * h), (-2.0 + 6.0 * u) / h];
    (n, d, dd)
}

/// Element matrices (row-major) of one element of length h: Hermite mass ∫N_iN_j, Hermite
/// bending stiffness ∫N_i''N_j'', linear mass, linear stiffness ∫L_i'L_j', cross mass
/// ∫N_i L_j (4×2), and load vectors ∫z N_i, ∫z L_i for an element starting at z0.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementMatrices {
    /// Hermite mass, 4×4.
    pub hermite_mass: [f64; 16],
    /// Hermite bending stiffness, 4×4.
    pub hermite_stiffness: [f64; 16],
    /// Linear mass, 2×2.
    pub linear_mass: [f64; 4],
    /// Linear stiffness, 2×2.
    pub linear_stiffness: [f64; 4],
    /// Cross mass ∫ N_i L_j, 4×2.
    pub cross_mass: [f64; 8],
    /// ∫ z N_i dz.
    pub load_hermite: [f64; 4],
    /// ∫ z L_i dz.
    pub load_linear: [f64; 2],
}

/// Compute the element matrices by Gauss quadrature.
pub fn element_matrices(z0: f64, h: f64) -> ElementMatrices {
    let mut e = ElementMatrices {
        hermite_mass: [0.0; 16],
        hermite_stiffness: [0.0; 16],
        linear_mass: [0.0; 4],
        linear_stiffness: [0.0; 4],
        cross_mass: [0.0; 8],
        load_hermite: [0.0; 4],
        load_linear: [0.0; 2],
    };
    for &(u, wq) in &GAUSS {
        let w = wq * h;
        let z = z0 + u * h;
        let (n, _, dd) = hermite(u, h);
        let l = [1.0 - u, u];
        let dl = [-1.0 / h, 1.0 / h];
        for i in 0..4 {
            for j in 0..4 {
                e.hermite_mass[i * 4 + j] += w * n[i] * n[j];
                e.hermite_stiffness[i * 4 + j] += w * dd[i] * dd[j];
            }
            for j in 0..2 {
                e.cross_mass[i * 2 + j] += w * n[i] * l[j];
            }
            e.load_hermite[i] += w * z * n[i];
        }
        for i in 0..2 {
            for j in 0..2 {
                e.linear_mass[i * 2 + j] += w * l[i] * l[j];
                e.linear_stiffness[i * 2 + j] += w * dl[i] * dl[j];
            }
            e.load_linear[i] += w * z * l[i];
        }
    }
    e
}

/// Node positions z_i = s·g(i/N) with g(u) = u − grading·sin(2πu)/(2π): uniform for
/// grading = 0; for 0 < grading < 1 the elements at the root and the tip are (1 − grading)
/// times the uniform size (the mapping is smooth, so the convergence order is kept).
pub fn node_positions(span: f64, elements: usize, grading: f64) -> Vec<f64> {
    use std::f64::consts::PI;
    let mut z: Vec<f64> = (0..=elements)
        .map(|i| {
            let u = i as f64 / elements as f64;
            span * (u - grading * (2.0 * PI * u).sin() / (2.0 * PI))
        })
        .collect();
    z[0] = 0.0;
    z[elements] = span;
    z
}

fn dof(node: usize, k: usize) -> Option<usize> {
    (node > 0).then(|| 3 * (node - 1) + k)
}

pub(crate) fn assemble(cfg: &Config, elements: usize) -> RawAssembly {
    let s = cfg.wing.span;
    let nodes = node_positions(s, elements, cfg.discretisation.grading);
    let n = 3 * elements;
    let mut b = builders(n);
    let mut load_q = vec![0.0; n];
    let mut load_t = vec![0.0; n];
    let (mut strain_q, mut strain_t) = (Vec::with_capacity(2 * elements), Vec::with_capacity(elements));
    for e in 0..elements {
        let h = nodes[e + 1] - nodes[e];
        // q'' is linear on the element: ∫q''² = h(m² + d²/3) with the mean m = (q'_{e+1} − q'_e)/h
        // and half-jump d = (κ1 − κ0)/2 = 6(q_e − q_{e+1})/h² + 3(q'_e + q'_{e+1})/h; θ' = Δθ/h.
        let (a, b) = (dof(e, 0), dof(e + 1, 0).expect("node e+1 > 0"));
        let row = |pivot: usize, coefs: [(Option<usize>, f64); 4], weight: f64| StrainRow {
            pivot,
            entries: coefs.iter().filter_map(|&(d, g)| d.map(|i| (i, g))).collect(),
            weight,
        };
        let (qa, pa, qb, pb) = (a, dof(e, 1), b, b + 1);
        strain_q.push(row(pb, [(pa, -1.0 / h), (Some(pb), 1.0 / h), (None, 0.0), (None, 0.0)], h));
        strain_q.push(row(
            qb,
            [(qa, 6.0 / (h * h)), (pa, 3.0 / h), (Some(qb), -6.0 / (h * h)), (Some(pb), 3.0 / h)],
            h / 3.0,
        ));
        strain_t.push(row(b + 2, [(dof(e, 2), -1.0 / h), (Some(b + 2), 1.0 / h), (None, 0.0), (None, 0.0)], h));
    }
    for e in 0..elements {
        let em = element_matrices(nodes[e], nodes[e + 1] - nodes[e]);
        let qd = [dof(e, 0), dof(e, 1), dof(e + 1, 0), dof(e + 1, 1)];
        let td = [dof(e, 2), dof(e + 1, 2)];
        b[0].add_block(&qd, &em.hermite_mass);
        b[3].add_block(&qd, &em.hermite_stiffness);
        b[1].add_block(&td, &em.linear_mass);
        b[4].add_block(&td, &em.linear_stiffness);
        for i in 0..4 {
            for j in 0..2 {
                if let (Some(a), Some(c)) = (qd[i], td[j]) {
                    b[2].add(a, c, em.cross_mass[i * 2 + j]);
                }
            }
            if let Some(a) = qd[i] {
                load_q[a] += em.load_hermite[i];
            }
        }
        for j in 0..2 {
            if let Some(c) = td[j] {
                load_t[c] += em.load_linear[j];
            }
        }
    }
    let mut x0 = vec![0.0; n];
    for node in 1..=elements {
        let z = nodes[node];
        let (q, dq) = initial_q(cfg, z);
        x0[3 * (node - 1)] = q;
        x0[3 * (node - 1) + 1] = dq;
        x0[3 * (node - 1) + 2] = initial_theta(cfg, z);
    }
    let z = output_grid(cfg);
    let mut q_rows = Vec::with_capacity(z.len());
    let mut theta_rows = Vec::with_capacity(z.len());
    for &zj in &z {
        let e = (nodes.partition_point(|&zn| zn <= zj).max(1) - 1).min(elements - 1);
        let h = nodes[e + 1] - nodes[e];
        let u = ((zj - nodes[e]) / h).clamp(0.0, 1.0);
        let (nv, _, _) = hermite(u, h);
        let qd = [dof(e, 0), dof(e, 1), dof(e + 1, 0), dof(e + 1, 1)];
        q_rows.push(qd.iter().zip(nv).filter_map(|(d, w)| d.map(|i| (i, w))).filter(|p| p.1 != 0.0).collect());
        let td = [(dof(e, 2), 1.0 - u), (dof(e + 1, 2), u)];
        theta_rows.push(td.iter().filter_map(|&(d, w)| d.map(|i| (i, w))).filter(|p| p.1 != 0.0).collect());
    }
    RawAssembly {
        parts: finish(b),
        load_q,
        load_t,
        tip_q: 3 * (elements - 1),
        tip_theta: 3 * (elements - 1) + 2,
        x0,
        interp: Interpolation { z, q_rows, theta_rows },
        strain_q,
        strain_t,
    }
}
