//! Elastic deformation of the half-space by the discrete-convolution FFT method (DC-FFT,
//! Liu, Wang & Liu 2000).
//!
//! The pressure is taken piecewise constant on rectangular cells of size `hx × hy` centred on the
//! grid nodes. The exact influence coefficient of a uniform unit pressure on one cell is the
//! integral of 1/r over the rectangle (Johnson, *Contact Mechanics*, §3.9):
//! ∬ dx′dy′/√((x−x′)²+(y−y′)²) = [F(x−x′, y−y′)] over the four corners with
//! F(x, y) = x·asinh(y/|x|) + y·asinh(x/|y|). The deformation on the grid is the linear
//! (aperiodic) convolution of these coefficients with the nodal pressures, computed by
//! zero-padding to at least 2n − 1 points per direction and a 2-D FFT. The FFT plans and the
//! transformed kernel are built once per grid shape and cell size and kept in a per-thread cache
//! (shared by all levels, restarts, load families and calls); the buffers are reused.

use rustfft::{num_complex::Complex, Fft, FftPlanner};
use std::sync::Arc;

/// x·asinh(y/|x|), continued by 0 at x = 0.
fn term(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        x * (y / x.abs()).asinh()
    }
}

/// F(x, y) = x·asinh(y/|x|) + y·asinh(x/|y|): a primitive of 1/r in both variables.
fn prim(x: f64, y: f64) -> f64 {
    term(x, y) + term(y, x)
}

/// ∬ 1/r over a rectangle of size `hx × hy` centred at the origin, seen from the point (x, y).
/// Lengths in any consistent unit; the result has that unit.
pub fn rect_influence(x: f64, y: f64, hx: f64, hy: f64) -> f64 {
    let (x1, x2) = (x - 0.5 * hx, x + 0.5 * hx);
    let (y1, y2) = (y - 0.5 * hy, y + 0.5 * hy);
    prim(x2, y2) - prim(x1, y2) - prim(x2, y1) + prim(x1, y1)
}

/// Smallest integer ≥ n whose prime factors are 2, 3 and 5 (fast FFT lengths).
fn smooth_length(n: usize) -> usize {
    let mut m = n.max(1);
    loop {
        let mut k = m;
        for p in [2, 3, 5] {
            while k % p == 0 {
                k /= p;
            }
        }
        if k == 1 {
            return m;
        }
        m += 1;
    }
}

/// The transformed kernel and the FFT plans of one grid shape and cell size, shared by every
/// [`Deformation`] of that shape (built once per thread, see [`kernel_cache_stats`]).
struct KernelPlan {
    lx: usize,
    ly: usize,
    /// Transformed kernel of the unscaled coefficients, transposed layout (index ix·ly + iy),
    /// only the lx/2 + 1 non-redundant x-frequencies, including 1/(lx·ly).
    kernel_hat: Vec<Complex<f64>>,
    fx: Arc<dyn Fft<f64>>,
    fxi: Arc<dyn Fft<f64>>,
    fy: Arc<dyn Fft<f64>>,
    fyi: Arc<dyn Fft<f64>>,
    scratch_len: usize,
}

impl KernelPlan {
    fn build(planner: &mut FftPlanner<f64>, nx: usize, ny: usize, hx: f64, hy: f64) -> Self {
        // Offsets −(n−1)…n−1 need 2n − 1 slots of a circular buffer, but the kernel is even, so
        // ±(n−1) may share one: 2n − 2 is exact, a power of two for the 2^k + 1 grids (512 for
        // 257², where 2n − 1 would give 540 = 2²·3³·5).
        let lx = smooth_length((2 * nx).saturating_sub(2).max(1));
        let ly = smooth_length((2 * ny).saturating_sub(2).max(1));
        let fx = planner.plan_fft_forward(lx);
        let fxi = planner.plan_fft_inverse(lx);
        let fy = planner.plan_fft_forward(ly);
        let fyi = planner.plan_fft_inverse(ly);
        let scratch_len = [&fx, &fxi, &fy, &fyi]
            .iter()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        // Kernel in circular layout, rows of length lx (x fastest). rect_influence is even in
        // both offsets: compute one quadrant and mirror it.
        let mut k = vec![Complex::new(0.0, 0.0); lx * ly];
        let norm = 1.0 / (lx * ly) as f64;
        // F at the cell corners ((i − ½)·hx, (j − ½)·hy), i, j = 0…n: each corner is shared by
        // four cells, and F is odd in each argument, so F(−½hx, ·) = −F(½hx, ·).
        let cx = |i: usize| (i as f64 - 0.5) * hx;
        let cy = |j: usize| (j as f64 - 0.5) * hy;
        let ncx = nx + 1;
        let mut corner = vec![0.0; ncx * (ny + 1)];
        for j in 1..=ny {
            for i in 1..=nx {
                corner[j * ncx + i] = prim(cx(i), cy(j));
            }
            corner[j * ncx] = -corner[j * ncx + 1];
        }
        for i in 0..ncx {
            corner[i] = -corner[ncx + i];
        }
        for dy in 0..ny {
            for dx in 0..nx {
                // rect_influence(dx·hx, dy·hy, hx, hy) from the corner table.
                let f = |i: usize, j: usize| corner[j * ncx + i];
                let v = (f(dx + 1, dy + 1) - f(dx, dy + 1) - f(dx + 1, dy) + f(dx, dy)) * norm;
                let c = Complex::new(v, 0.0);
                let ixs = [dx, (lx - dx) % lx];
                let iys = [dy, (ly - dy) % ly];
                for iy in iys {
                    for ix in ixs {
                        k[iy * lx + ix] = c;
                    }
                }
            }
        }
        let mut scratch = vec![Complex::new(0.0, 0.0); scratch_len];
        fx.process_with_scratch(&mut k, &mut scratch);
        let nc = lx / 2 + 1;
        let mut kt = vec![Complex::new(0.0, 0.0); nc * ly];
        for iy in 0..ly {
            for ix in 0..nc {
                kt[ix * ly + iy] = k[iy * lx + ix];
            }
        }
        fy.process_with_scratch(&mut kt, &mut scratch);
        KernelPlan {
            lx,
            ly,
            kernel_hat: kt,
            fx,
            fxi,
            fy,
            fyi,
            scratch_len,
        }
    }

    fn bytes(&self) -> usize {
        self.kernel_hat.len() * std::mem::size_of::<Complex<f64>>()
    }
}

/// Largest total size of the kernels kept per thread, bytes (the 257² kernel takes 2.3 MB, the
/// 1025² one 37 MB). The least recently used kernels are dropped above it.
const KERNEL_CACHE_BYTES: usize = 96 << 20;

/// Cache key: grid shape (nx, ny) and the bits of the cell size (hx, hy).
type KernelKey = (usize, usize, u64, u64);

/// Per-thread store of kernels and FFT plans, keyed by the grid shape and the cell size.
struct KernelCache {
    planner: FftPlanner<f64>,
    /// (nx, ny, hx bits, hy bits) → kernel, most recently used last.
    entries: Vec<(KernelKey, Arc<KernelPlan>)>,
    enabled: bool,
    hits: u64,
    misses: u64,
}

thread_local! {
    static KERNELS: std::cell::RefCell<KernelCache> = std::cell::RefCell::new(KernelCache {
        planner: FftPlanner::new(),
        entries: Vec::new(),
        enabled: true,
        hits: 0,
        misses: 0,
    });
}

fn kernel_plan(nx: usize, ny: usize, hx: f64, hy: f64) -> Arc<KernelPlan> {
    KERNELS.with(|c| {
        let mut c = c.borrow_mut();
        let key = (nx, ny, hx.to_bits(), hy.to_bits());
        if c.enabled {
            if let Some(pos) = c.entries.iter().position(|(k, _)| *k == key) {
                let e = c.entries.remove(pos);
                let plan = e.1.clone();
                c.entries.push(e);
                c.hits += 1;
                return plan;
            }
        }
        c.misses += 1;
        let plan = Arc::new(KernelPlan::build(&mut c.planner, nx, ny, hx, hy));
        if c.enabled {
            c.entries.push((key, plan.clone()));
            let mut total: usize = c.entries.iter().map(|(_, p)| p.bytes()).sum();
            while total > KERNEL_CACHE_BYTES && c.entries.len() > 1 {
                total -= c.entries[0].1.bytes();
                c.entries.remove(0);
            }
        }
        plan
    })
}

/// Kernel cache of the calling thread: (kernels reused, kernels built) since the thread started
/// or since the last [`set_kernel_cache`] call. For benchmarks and tests.
pub fn kernel_cache_stats() -> (u64, u64) {
    KERNELS.with(|c| {
        let c = c.borrow();
        (c.hits, c.misses)
    })
}

/// Turns the calling thread's kernel cache on (default) or off, empties it and resets its
/// counters. Off, every [`Deformation::new`] builds its kernel afresh (the behaviour before the
/// cache; the FFT plans still come from the thread's planner; for before/after benchmarks).
/// Results are identical either way.
pub fn set_kernel_cache(enabled: bool) {
    KERNELS.with(|c| {
        let mut c = c.borrow_mut();
        c.enabled = enabled;
        c.entries.clear();
        c.hits = 0;
        c.misses = 0;
        if !enabled {
            c.planner = FftPlanner::new();
        }
    })
}

/// FFT convolution of nodal pressures with the rectangle influence coefficients on an `nx × ny`
/// grid (x index fastest), scaled by a constant factor.
///
/// The transformed kernel and the FFT plans depend only on the grid shape and the cell size;
/// they are kept in a per-thread cache (bounded, least recently used dropped) and shared by
/// every `Deformation` of the same shape — the levels of a solver, its restarts, the members
/// of a load family and later calls. Only the work buffers belong to one `Deformation`.
pub struct Deformation {
    nx: usize,
    ny: usize,
    plan: Arc<KernelPlan>,
    rows: Vec<Complex<f64>>,
    cols: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
    hx: f64,
    hy: f64,
    scale: f64,
}

impl std::fmt::Debug for Deformation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Deformation")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("lx", &self.plan.lx)
            .field("ly", &self.plan.ly)
            .finish()
    }
}

impl Clone for Deformation {
    fn clone(&self) -> Self {
        Deformation::with_plan(
            self.nx,
            self.ny,
            self.plan.clone(),
            self.hx,
            self.hy,
            self.scale,
        )
    }
}

impl Deformation {
    /// Plans the convolution for an `nx × ny` grid with spacings `hx`, `hy` (same length unit) and
    /// overall factor `scale` (deformation = scale · Σ K·P). The kernel and plans come from the
    /// thread's cache when a grid of the same shape and cell size was planned before.
    pub fn new(nx: usize, ny: usize, hx: f64, hy: f64, scale: f64) -> Self {
        let plan = kernel_plan(nx, ny, hx, hy);
        Deformation::with_plan(nx, ny, plan, hx, hy, scale)
    }

    fn with_plan(
        nx: usize,
        ny: usize,
        plan: Arc<KernelPlan>,
        hx: f64,
        hy: f64,
        scale: f64,
    ) -> Self {
        let (lx, ly) = (plan.lx, plan.ly);
        let zero = Complex::new(0.0, 0.0);
        Deformation {
            nx,
            ny,
            rows: vec![zero; lx * ny.div_ceil(2)],
            cols: vec![zero; (lx / 2 + 1) * ly],
            scratch: vec![zero; plan.scratch_len],
            plan,
            hx,
            hy,
            scale,
        }
    }

    /// Changes the overall factor (deformation = scale · Σ K·P) without replanning.
    pub fn set_scale(&mut self, scale: f64) {
        self.scale = scale;
    }

    /// Influence coefficient (scaled) of node offset (dx, dy).
    pub fn coefficient(&self, dx: isize, dy: isize) -> f64 {
        self.scale * rect_influence(dx as f64 * self.hx, dy as f64 * self.hy, self.hx, self.hy)
    }

    /// Computes `out[i + nx·j] = scale · Σ_kl K(i−k, j−l)·p[k + nx·l]`.
    ///
    /// Rows are real: two rows are packed into one complex FFT along x (real and imaginary part),
    /// and only the lx/2 + 1 non-redundant x-frequencies are transformed along y.
    pub fn apply(&mut self, p: &[f64], out: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        let plan = &*self.plan;
        let (lx, ly) = (plan.lx, plan.ly);
        debug_assert_eq!(p.len(), nx * ny);
        debug_assert_eq!(out.len(), nx * ny);
        let zero = Complex::new(0.0, 0.0);
        let npairs = ny.div_ceil(2);
        // Forward along x: row pair q holds rows 2q (real part) and 2q + 1 (imaginary part).
        for q in 0..npairs {
            let (j0, j1) = (2 * q, 2 * q + 1);
            let row = &mut self.rows[q * lx..(q + 1) * lx];
            for i in 0..nx {
                let b = if j1 < ny { p[j1 * nx + i] } else { 0.0 };
                row[i] = Complex::new(p[j0 * nx + i], b);
            }
            for c in row[nx..].iter_mut() {
                *c = zero;
            }
        }
        let packed = npairs * lx;
        plan.fx
            .process_with_scratch(&mut self.rows[..packed], &mut self.scratch);
        // Unpack the two spectra into columns (zero-padded in y): A[k] = (Z[k] + Z*[−k])/2,
        // B[k] = (Z[k] − Z*[−k])/(2i).
        let nc = lx / 2 + 1;
        for ix in 0..nc {
            let mx = (lx - ix) % lx;
            for q in 0..npairs {
                let z = self.rows[q * lx + ix];
                let zm = self.rows[q * lx + mx].conj();
                let a = (z + zm) * 0.5;
                let d = (z - zm) * 0.5;
                let b = Complex::new(d.im, -d.re);
                self.cols[ix * ly + 2 * q] = a;
                if 2 * q + 1 < ny {
                    self.cols[ix * ly + 2 * q + 1] = b;
                }
            }
            for c in self.cols[ix * ly + ny..(ix + 1) * ly].iter_mut() {
                *c = zero;
            }
        }
        let used = nc * ly;
        plan.fy
            .process_with_scratch(&mut self.cols[..used], &mut self.scratch);
        for (c, k) in self.cols[..used].iter_mut().zip(&plan.kernel_hat) {
            *c *= *k;
        }
        plan.fyi
            .process_with_scratch(&mut self.cols[..used], &mut self.scratch);
        // Repack: Z[k] = S_2q[k] + i·S_2q+1[k] with the Hermitian completion S[lx − k] = S*[k];
        // the inverse transform returns row 2q in the real and row 2q + 1 in the imaginary part.
        let i_unit = Complex::new(0.0, 1.0);
        for q in 0..npairs {
            let (j0, j1) = (2 * q, 2 * q + 1);
            for ix in 0..lx {
                let (src, conj) = if ix < nc {
                    (ix, false)
                } else {
                    (lx - ix, true)
                };
                let mut s0 = self.cols[src * ly + j0];
                let mut s1 = if j1 < ny {
                    self.cols[src * ly + j1]
                } else {
                    zero
                };
                if conj {
                    s0 = s0.conj();
                    s1 = s1.conj();
                }
                self.rows[q * lx + ix] = s0 + i_unit * s1;
            }
        }
        plan.fxi
            .process_with_scratch(&mut self.rows[..packed], &mut self.scratch);
        let scale = self.scale;
        for q in 0..npairs {
            let (j0, j1) = (2 * q, 2 * q + 1);
            for i in 0..nx {
                let v = self.rows[q * lx + i];
                out[j0 * nx + i] = scale * v.re;
                if j1 < ny {
                    out[j1 * nx + i] = scale * v.im;
                }
            }
        }
    }

    /// Direct O(n²) summation, for tests: same result as [`Deformation::apply`] to round-off.
    pub fn apply_direct(&self, p: &[f64], out: &mut [f64]) {
        let (nx, ny) = (self.nx, self.ny);
        for j in 0..ny {
            for i in 0..nx {
                let mut s = 0.0;
                for l in 0..ny {
                    for k in 0..nx {
                        let pk = p[l * nx + k];
                        if pk != 0.0 {
                            s += pk
                                * rect_influence(
                                    (i as f64 - k as f64) * self.hx,
                                    (j as f64 - l as f64) * self.hy,
                                    self.hx,
                                    self.hy,
                                );
                        }
                    }
                }
                out[j * nx + i] = self.scale * s;
            }
        }
    }
}
