//! Element matrices: the 2-node Euler–Bernoulli beam (Hermite cubics, 2 DOF per node) and the
//! 2-node 3D frame element (6 DOF per node), both with consistent mass.
//!
//! Hand-written: these are the textbook matrices (Przemieniecki, *Theory of Matrix Structural
//! Analysis*, §5 and §11); no crate provides them in this form.

/// Stiffness of a Hermite beam element in the DOFs (w₁, φ₁, w₂, φ₂), φ = dw/dx:
/// k = EI/h³ · [[12, 6h, −12, 6h], [6h, 4h², −6h, 2h²], [−12, −6h, 12, −6h], [6h, 2h², −6h, 4h²]].
pub fn beam_stiffness(flexural_rigidity: f64, h: f64) -> [[f64; 4]; 4] {
    let c = flexural_rigidity / (h * h * h);
    let h2 = h * h;
    [
        [12.0 * c, 6.0 * h * c, -12.0 * c, 6.0 * h * c],
        [6.0 * h * c, 4.0 * h2 * c, -6.0 * h * c, 2.0 * h2 * c],
        [-12.0 * c, -6.0 * h * c, 12.0 * c, -6.0 * h * c],
        [6.0 * h * c, 2.0 * h2 * c, -6.0 * h * c, 4.0 * h2 * c],
    ]
}

/// Consistent mass of a Hermite beam element in (w₁, φ₁, w₂, φ₂), mass per length m̄ [kg/m]:
/// m = m̄h/420 · [[156, 22h, 54, −13h], [22h, 4h², 13h, −3h²], [54, 13h, 156, −22h],
/// [−13h, −3h², −22h, 4h²]].
pub fn beam_mass(mass_per_length: f64, h: f64) -> [[f64; 4]; 4] {
    let c = mass_per_length * h / 420.0;
    let h2 = h * h;
    [
        [156.0 * c, 22.0 * h * c, 54.0 * c, -13.0 * h * c],
        [22.0 * h * c, 4.0 * h2 * c, 13.0 * h * c, -3.0 * h2 * c],
        [54.0 * c, 13.0 * h * c, 156.0 * c, -22.0 * h * c],
        [-13.0 * h * c, -3.0 * h2 * c, -22.0 * h * c, 4.0 * h2 * c],
    ]
}

/// Stiffness and mass data of one frame member.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameProperties {
    /// Axial rigidity EA [N].
    pub axial_rigidity: f64,
    /// Flexural rigidity in the vertical plane E·I_y [N·m²].
    pub flexural_rigidity_y: f64,
    /// Flexural rigidity in the horizontal plane E·I_z [N·m²].
    pub flexural_rigidity_z: f64,
    /// Torsional rigidity G·J [N·m²].
    pub torsional_rigidity: f64,
    /// Translational mass per length m̄ [kg/m] (structure plus added mass).
    pub mass_per_length: f64,
    /// Polar mass moment of inertia per length about the member axis [kg·m²/m].
    pub polar_inertia_per_length: f64,
}

/// Local frame DOF order per node: u, v, w, θx, θy, θz (x along the member, z up, y = z × x).
/// In the vertical plane the Hermite slope is φ = dw/dx = −θy, hence the sign factors below.
pub const VERTICAL_PLANE_DOFS: [usize; 4] = [2, 4, 8, 10];
/// Sign of each of [`VERTICAL_PLANE_DOFS`] in the Hermite variables (w₁, φ₁, w₂, φ₂).
pub const VERTICAL_PLANE_SIGNS: [f64; 4] = [1.0, -1.0, 1.0, -1.0];
const HORIZONTAL_PLANE_DOFS: [usize; 4] = [1, 5, 7, 11];

/// Local stiffness and consistent mass (12 × 12) of a straight 3D frame element of length `h`:
/// axial EA/h and torsion GJ/h bars, Hermite bending in both planes; mass m̄h/6·[2 1; 1 2] in
/// axial and in torsion (with the polar inertia), Hermite consistent mass in bending.
pub fn frame_local(p: &FrameProperties, h: f64) -> ([[f64; 12]; 12], [[f64; 12]; 12]) {
    let mut k = [[0.0; 12]; 12];
    let mut m = [[0.0; 12]; 12];
    let bar = |mat: &mut [[f64; 12]; 12], a: usize, b: usize, diag: f64, off: f64| {
        mat[a][a] += diag;
        mat[b][b] += diag;
        mat[a][b] += off;
        mat[b][a] += off;
    };
    bar(&mut k, 0, 6, p.axial_rigidity / h, -p.axial_rigidity / h);
    bar(
        &mut k,
        3,
        9,
        p.torsional_rigidity / h,
        -p.torsional_rigidity / h,
    );
    let axial_mass = p.mass_per_length * h / 6.0;
    bar(&mut m, 0, 6, 2.0 * axial_mass, axial_mass);
    let polar = p.polar_inertia_per_length * h / 6.0;
    bar(&mut m, 3, 9, 2.0 * polar, polar);
    let bend_mass = beam_mass(p.mass_per_length, h);
    for (dofs, signs, rigidity) in [
        (
            VERTICAL_PLANE_DOFS,
            VERTICAL_PLANE_SIGNS,
            p.flexural_rigidity_y,
        ),
        (HORIZONTAL_PLANE_DOFS, [1.0; 4], p.flexural_rigidity_z),
    ] {
        let bend = beam_stiffness(rigidity, h);
        for i in 0..4 {
            for j in 0..4 {
                let s = signs[i] * signs[j];
                k[dofs[i]][dofs[j]] += s * bend[i][j];
                m[dofs[i]][dofs[j]] += s * bend_mass[i][j];
            }
        }
    }
    (k, m)
}

/// Rotation from global to local axes of a horizontal member along the unit vector
/// (cos α, sin α, 0): rows are the local x, y = z × x, z = global z.
pub fn horizontal_rotation(direction: [f64; 2]) -> [[f64; 3]; 3] {
    let [c, s] = direction;
    [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]
}

/// K_global = Tᵀ K_local T with T = diag(R, R, R, R).
pub fn to_global(local: &[[f64; 12]; 12], rotation: &[[f64; 3]; 3]) -> [[f64; 12]; 12] {
    // A·T: rotate the columns block by block, then Tᵀ·(A·T): the rows.
    let mut at = [[0.0; 12]; 12];
    for i in 0..12 {
        for block in 0..4 {
            for c in 0..3 {
                let mut sum = 0.0;
                for r in 0..3 {
                    sum += local[i][3 * block + r] * rotation[r][c];
                }
                at[i][3 * block + c] = sum;
            }
        }
    }
    let mut out = [[0.0; 12]; 12];
    for j in 0..12 {
        for block in 0..4 {
            for c in 0..3 {
                let mut sum = 0.0;
                for r in 0..3 {
                    sum += rotation[r][c] * at[3 * block + r][j];
                }
                out[3 * block + c][j] = sum;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn properties() -> FrameProperties {
        FrameProperties {
            axial_rigidity: 3.0e10,
            flexural_rigidity_y: 2.0e10,
            flexural_rigidity_z: 5.0e10,
            torsional_rigidity: 1.0e10,
            mass_per_length: 4000.0,
            polar_inertia_per_length: 900.0,
        }
    }

    fn symmetric<const N: usize>(a: &[[f64; N]; N]) -> bool {
        let scale = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
        (0..N).all(|i| (0..N).all(|j| (a[i][j] - a[j][i]).abs() <= 1e-14 * scale))
    }

    #[test]
    fn beam_element_is_symmetric_and_has_the_two_rigid_body_modes_in_its_null_space() {
        let h = 1.7;
        let k = beam_stiffness(3.0e9, h);
        assert!(symmetric(&k) && symmetric(&beam_mass(1000.0, h)));
        // Rigid translation (1, 0, 1, 0) and rigid rotation (0, 1, h, 1) about node 1.
        let scale = k.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs())) * h;
        for mode in [[1.0, 0.0, 1.0, 0.0], [0.0, 1.0, h, 1.0]] {
            for row in &k {
                let f: f64 = row.iter().zip(mode).map(|(a, b)| a * b).sum();
                // Cancellation of four terms of size ≤ max|k|·h: round-off ~1e-16 of that.
                assert!(f.abs() < 1e-14 * scale, "{f}");
            }
        }
        // The consistent mass integrates to the element mass: 1ᵀ M_ww 1 = m̄h.
        let m = beam_mass(1000.0, h);
        let total = m[0][0] + m[0][2] + m[2][0] + m[2][2];
        assert!((total - 1000.0 * h).abs() < 1e-9);
    }

    /// Rigid-body motions of a frame element from node 1 to node 2 = node 1 + (d, 0, 0) in
    /// local axes: three translations and three rotations (u = θ × r).
    fn rigid_modes(d: [f64; 3]) -> Vec<[f64; 12]> {
        let mut modes = Vec::new();
        for axis in 0..3 {
            let mut t = [0.0; 12];
            t[axis] = 1.0;
            t[6 + axis] = 1.0;
            modes.push(t);
        }
        for axis in 0..3 {
            let mut theta = [0.0; 3];
            theta[axis] = 1.0;
            let cross = [
                theta[1] * d[2] - theta[2] * d[1],
                theta[2] * d[0] - theta[0] * d[2],
                theta[0] * d[1] - theta[1] * d[0],
            ];
            let mut r = [0.0; 12];
            r[3 + axis] = 1.0;
            r[9 + axis] = 1.0;
            r[6..9].copy_from_slice(&cross);
            modes.push(r);
        }
        modes
    }

    #[test]
    fn frame_element_is_symmetric_with_six_rigid_body_modes_in_any_direction() {
        let h = 2.5;
        let (k, m) = frame_local(&properties(), h);
        assert!(symmetric(&k) && symmetric(&m));
        for angle in [0.0f64, 0.5 * std::f64::consts::PI, 0.7] {
            let direction = [angle.cos(), angle.sin()];
            let kg = to_global(&k, &horizontal_rotation(direction));
            assert!(symmetric(&kg));
            let d = [h * direction[0], h * direction[1], 0.0];
            let scale = kg.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs())) * h;
            for mode in rigid_modes(d) {
                for row in &kg {
                    let f: f64 = row.iter().zip(mode).map(|(a, b)| a * b).sum();
                    // Cancellation of twelve terms of size ≤ max|k|·h after a rotation:
                    // round-off ~1e-15 of that.
                    assert!(f.abs() < 1e-13 * scale, "angle {angle}: {f}");
                }
            }
        }
    }

    #[test]
    fn vertical_bending_of_the_frame_element_uses_theta_y_equal_to_minus_the_slope() {
        // A rigid rotation that lifts node 2 (w₂ = h·φ) has θy = −φ at both ends.
        let h = 2.0;
        let (k, _) = frame_local(&properties(), h);
        let mut u = [0.0; 12];
        u[4] = -1.0;
        u[10] = -1.0;
        u[8] = h;
        let scale = k.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs())) * h;
        for row in &k {
            let f: f64 = row.iter().zip(u).map(|(a, b)| a * b).sum();
            // Exact cancellation up to round-off.
            assert!(f.abs() < 1e-14 * scale);
        }
    }
}
