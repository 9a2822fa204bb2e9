!> Persson's theory: the full-contact identity, elastic limits, the small-load area, one wave in
!> closed form, symmetries, bad input
module test_veslide_persson
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit
    use veslide_kinds, only: dp, i8, pi, two_pi
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_one_term, new_elastic
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use veslide_spectrum, only: slope_tensor
    use veslide_surface, only: psd_t, random_surface, cosine_surface, rms_height
    use veslide_persson, only: persson_t, persson_estimate
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: square_grid
    use reference_oracles, only: paper_rough, paper_solid, peak_speed, full_contact_force, einf, tau, lcell
    implicit none
    private
    public :: collect_persson

    real(dp), parameter :: ratio = 11.0_dp
    character(len=*), parameter :: prefix = "veslide:persson:persson_estimate: "

contains

    subroutine collect_persson(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("full-contact-is-exact", test_full_contact), &
            new_unittest("elastic-limits-have-no-friction", test_elastic_limits), &
            new_unittest("small-load-area-is-sqrt-8-over-pi", test_small_load), &
            new_unittest("single-wave-closed-form", test_single_wave), &
            new_unittest("symmetries-reverse-mirror-rotate", test_symmetries), &
            new_unittest("one-shell-per-distinct-norm", test_shells), &
            new_unittest("bad-input-names-the-variable", test_bad_input), &
            new_unittest("zero-pressure-is-rejected", test_zero_pressure, should_fail=.true., &
                         expect="veslide:persson:persson_estimate: p_mean_pa must be positive") &
            ]
    end subroutine collect_persson

    !> a_q: the r2c transform of h divided by nx*ny
    subroutine spectrum(h, hk, error)
        real(dp), intent(in) :: h(:, :)
        complex(dp), allocatable, intent(out) :: hk(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: fft
        call fft%init(size(h, 1), size(h, 2), error, planner='estimate'); if (allocated(error)) return
        fft%x = h
        call fft%forward()
        hk = fft%k/(real(size(h, 1), dp)*real(size(h, 2), dp))
        call fft%destroy()
    end subroutine spectrum

    !> Estimate for heights h on the lcell^2 cell
    subroutine estimate(h, mat, v, p0, res, error, s_correction)
        real(dp), intent(in) :: h(:, :), v(2), p0
        type(material_t), intent(in) :: mat
        type(persson_t), intent(out) :: res
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: s_correction
        complex(dp), allocatable :: hk(:, :)
        type(kernel_t) :: k
        call spectrum(h, hk, error); if (allocated(error)) return
        call new_kernel(k, square_grid(h, lcell, lcell), mat, v, KERNEL_SPECTRAL, error); if (allocated(error)) return
        call persson_estimate(k, hk, p0, res, error, s_correction)
    end subroutine estimate

    !> Estimate for the half-spectrum hk on an nx x ny grid of an lx x ly cell
    subroutine estimate_hk(nx, ny, lx, ly, hk, mat, v, p0, res, error)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: lx, ly, v(2), p0
        complex(dp), intent(in) :: hk(:, :)
        type(material_t), intent(in) :: mat
        type(persson_t), intent(out) :: res
        type(error_t), allocatable, intent(out) :: error
        type(grid_t) :: g
        type(kernel_t) :: k
        call new_grid(g, nx, ny, lx, ly, error); if (allocated(error)) return
        call new_kernel(k, g, mat, v, KERNEL_SPECTRAL, error); if (allocated(error)) return
        call persson_estimate(k, hk, p0, res, error)
    end subroutine estimate_hk

    !> With P = S = 1 (p0 so high that P(q_max) rounds to 1) the force is the exact full-contact
    !> force of the same surface, F = -(1/N^4) sum_q w q Im K |H/K|^2, K the solver's spectral kernel.
    !> Anisotropic surface (eps 0.5, alpha 30 deg) plus waves on both Nyquist lines, v at 20 deg at
    !> the loss peak of the wavelength L/4. Only the rounding of two sums of ~2000 terms separates
    !> the two: 1e-12 relative to |F|.
    subroutine test_full_contact(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        type(material_t) :: m
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(persson_t) :: r1, rs
        real(dp) :: h(n, n), v(2), fe(2), amp, e1, es
        integer :: i, j
        call paper_rough(n, h, error, eps=0.5_dp, alpha=pi/6); if (allocated(error)) return
        amp = 0.02_dp*rms_height(h)
        do j = 1, n
            do i = 1, n
                h(i, j) = h(i, j) + amp*((-1.0_dp)**(i - 1)*cos(two_pi*3*(j - 1)/n) &
                                         + (-1.0_dp)**(j - 1)*cos(two_pi*5*(i - 1)/n + 0.3_dp) &
                                         + 0.5_dp*(-1.0_dp)**(i + j))
            end do
        end do
        call paper_solid(ratio, m, error); if (allocated(error)) return
        v = peak_speed(ratio, 4.0_dp)*[cos(pi/9), sin(pi/9)]
        call estimate(h, m, v, 1.0e20_dp, r1, error); if (allocated(error)) return
        call estimate(h, m, v, 1.0e20_dp, rs, error, s_correction=.true.); if (allocated(error)) return
        ! the exact full-contact force of the boundary elements (the shared oracle)
        call new_kernel(k, square_grid(h, lcell, lcell), m, v, KERNEL_SPECTRAL, error); if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        fe = full_contact_force(k, fft, h)
        e1 = norm2(r1%force_pa - fe)/norm2(fe); es = norm2(rs%force_pa - fe)/norm2(fe)
        call report("|F - F_exact|/|F_exact| S=1", e1); call report("S corrected", es)
        call report("F_exact.v_hat [Pa]", dot_product(fe, v)/norm2(v))
        call check(error, r1%contact_area_fraction, 1.0_dp, "P(q_max) must round to 1", abs=0.0_dp)
        if (allocated(error)) return
        call check(error, dot_product(fe, v) < 0.0_dp, "the exact force must resist the motion")
        if (allocated(error)) return
        call check(error, e1 <= 1.0e-12_dp, "full contact, S = 1: F differs from the exact force")
        if (allocated(error)) return
        call check(error, es <= 1.0e-12_dp, "full contact, S corrected: F differs from the exact force")
    end subroutine test_full_contact

    !> No dissipation without loss: an elastic solid at speed, and the viscoelastic solid at v -> 0
    !> and v -> infinity (along x, isotropic surface), give no force; at v = 0 the area is that of the
    !> elastic solid E0. The residual force decays as 1/(w tau), ~1e-12 of the peak here; bound 1e-9
    !> of the friction at the loss peak. The fast area is that of the glassy solid only for an oblique
    !> v (20 deg: no lattice mode has q.v = 0); along x the modes with q_x = 0 are still felt at w = 0,
    !> i.e. with E0, so the area lies above the glassy one.
    subroutine test_elastic_limits(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        real(dp), parameter :: p0 = 32.0e3_dp
        type(material_t) :: m, e0, ei
        type(persson_t) :: rpk, rel, r0, re0, rfast, rei, rslow, robl
        real(dp) :: h(n, n), vpk, d0, di
        call paper_rough(n, h, error); if (allocated(error)) return
        call paper_solid(ratio, m, error); if (allocated(error)) return
        call new_elastic(e0, einf/ratio, 0.5_dp, error); if (allocated(error)) return
        call new_elastic(ei, einf, 0.5_dp, error); if (allocated(error)) return
        vpk = peak_speed(ratio, 4.0_dp)
        call estimate(h, m, [vpk, 0.0_dp], p0, rpk, error); if (allocated(error)) return
        call estimate(h, e0, vpk*[cos(pi/9), sin(pi/9)], p0, rel, error); if (allocated(error)) return
        call estimate(h, m, [0.0_dp, 0.0_dp], p0, r0, error); if (allocated(error)) return
        call estimate(h, e0, [0.0_dp, 0.0_dp], p0, re0, error); if (allocated(error)) return
        call estimate(h, m, [1.0e-12_dp*vpk, 0.0_dp], p0, rslow, error); if (allocated(error)) return
        call estimate(h, m, [1.0e12_dp*vpk, 0.0_dp], p0, rfast, error); if (allocated(error)) return
        call estimate(h, m, 1.0e12_dp*vpk*[cos(pi/9), sin(pi/9)], p0, robl, error); if (allocated(error)) return
        call estimate(h, ei, [0.0_dp, 0.0_dp], p0, rei, error); if (allocated(error)) return
        d0 = maxval(abs(r0%area_fraction - re0%area_fraction))
        di = maxval(abs(robl%area_fraction - rei%area_fraction))
        call report("mu at peak", rpk%friction_coefficient)
        call report("elastic |F|/p0", norm2(rel%force_pa)/p0)
        call report("v=0 |F|/p0", norm2(r0%force_pa)/p0)
        call report("slow mu/mu_pk", rslow%friction_coefficient/rpk%friction_coefficient)
        call report("fast mu/mu_pk", rfast%friction_coefficient/rpk%friction_coefficient)
        call report("fast lat/mu_pk", rfast%lateral_force_ratio/rpk%friction_coefficient)
        call report("v=0 max|dP| vs E0", d0); call report("fast 20deg max|dP| vs Einf", di)
        call report("fast along x A/A0", rfast%contact_area_fraction)
        call report("A/A0 E0", re0%contact_area_fraction); call report("A/A0 Einf", rei%contact_area_fraction)
        call check(error, rpk%friction_coefficient > 1.0e-2_dp, "no friction at the loss peak")
        if (allocated(error)) return
        call check(error, maxval(abs(rel%force_pa))/p0 <= 1.0e-15_dp, "elastic solid at speed has a force")
        if (allocated(error)) return
        call check(error, maxval(abs(r0%force_pa))/p0 <= 1.0e-15_dp, "force at v = 0"); if (allocated(error)) return
        call check(error, abs(rslow%friction_coefficient) <= 1.0e-9_dp*rpk%friction_coefficient, "friction v -> 0")
        if (allocated(error)) return
        call check(error, abs(rslow%lateral_force_ratio) <= 1.0e-9_dp*rpk%friction_coefficient, "lateral v -> 0")
        if (allocated(error)) return
        call check(error, abs(rfast%friction_coefficient) <= 1.0e-9_dp*rpk%friction_coefficient, "friction v -> inf")
        if (allocated(error)) return
        call check(error, abs(rfast%lateral_force_ratio) <= 1.0e-9_dp*rpk%friction_coefficient, "lateral v -> inf")
        if (allocated(error)) return
        call check(error, size(r0%area_fraction) == size(re0%area_fraction), "shells differ"); if (allocated(error)) return
        call check(error, d0 <= 1.0e-14_dp, "area at v = 0 is not the E0 area"); if (allocated(error)) return
        call check(error, size(robl%area_fraction) == size(rei%area_fraction), "shells differ"); if (allocated(error)) return
        call check(error, di <= 1.0e-12_dp, "area at v -> inf (20 deg) is not the Einf area"); if (allocated(error)) return
        call check(error, rfast%contact_area_fraction > rei%contact_area_fraction*(1.0_dp + 1.0e-6_dp), &
                   "along x the q_x = 0 modes must keep the area above the glassy one")
        if (allocated(error)) return
        call check(error, rei%contact_area_fraction < re0%contact_area_fraction, "the glassy solid must touch less")
    end subroutine test_elastic_limits

    !> Elastic solid at small load: A/A0 = erf(x), x = sqrt(2) p0/(E* s), s^2 = m20 + m02 (the
    !> slope-tensor trace, measured independently by veslide_surface). The linear law is
    !> sqrt(8/pi) p0/(E* s) = 2x/sqrt(pi); erf(x) sqrt(pi)/(2x) = 1 - x^2/3 + x^4/10 - ..., an alternating
    !> series with decreasing terms for x < 1, so the relative deviation dev from the linear law obeys
    !> 0 <= dev + x^2/3 <= x^4/10. At x = 0.02: dev = -1.33e-4, bracket 1.6e-8 (plus 1e-13 of rounding).
    !> Also: P(q) does not increase with q, and its last value is the area.
    subroutine test_small_load(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        real(dp), parameter :: x = 0.02_dp
        type(material_t) :: e
        type(fft2d_t) :: fft
        type(persson_t) :: r
        real(dp) :: h(n, n), mt(2, 2), s, estar, p0, alin, dev
        call paper_rough(n, h, error, eps=0.5_dp, alpha=pi/6); if (allocated(error)) return
        call new_elastic(e, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        estar = 1.0e7_dp/(1.0_dp - 0.25_dp)
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        call slope_tensor(square_grid(h, lcell, lcell), fft, h, mt)
        s = sqrt(mt(1, 1) + mt(2, 2))
        p0 = x*estar*s/sqrt(2.0_dp)
        call estimate(h, e, [0.0_dp, 0.0_dp], p0, r, error); if (allocated(error)) return
        alin = sqrt(8.0_dp/pi)*p0/(estar*s)
        dev = r%contact_area_fraction/alin - 1.0_dp
        call report("A/A0", r%contact_area_fraction); call report("rel. dev. from linear", dev)
        call report("dev + x^2/3", dev + x**2/3.0_dp); call report("bound x^4/10", x**4/10.0_dp)
        call check(error, dev + x**2/3.0_dp >= -1.0e-13_dp .and. dev + x**2/3.0_dp <= x**4/10.0_dp + 1.0e-13_dp, &
                   "A/A0 against sqrt(8/pi) p0/(E* s): dev + x^2/3 not in [0, x^4/10]")
        if (allocated(error)) return
        call check(error, all(r%q_per_m(2:) > r%q_per_m(:size(r%q_per_m) - 1)), "shells not strictly ascending")
        if (allocated(error)) return
        call check(error, all(r%area_fraction(2:) <= r%area_fraction(:size(r%area_fraction) - 1)), &
                   "P(q) increases with q")
        if (allocated(error)) return
        call check(error, r%contact_area_fraction, r%area_fraction(size(r%area_fraction)), "area is P(q_max)", abs=0.0_dp)
    end subroutine test_small_load

    !> h = h0 cos(q.x), q = (3, 2) q0, v along +x at the loss peak, p0 = p1/2 with p1 = |q| |E*(q.v)| h0/2
    !> the full-contact pressure amplitude. By hand, with a_{+-q} = h0/2:
    !>   G = (1/(2 p0^2)) 2 |z|^2 h0^2/4 = (p1/(2 p0))^2,  so P = erf(p0/p1) (here erf(1/2));
    !>   F = 2 q Im z P S h0^2/4 = -q |q| h0^2 P S E*''(q.v)/4: parallel to -q for q.v > 0,
    !>   so friction = F_x/(-p0) > 0 and lateral/friction = -q_y/q_x = -tan(beta).
    !> Other modes carry only the FFT's rounding (~1e-17 h0), so 1e-12 relative.
    subroutine test_single_wave(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 32
        real(dp), parameter :: h0 = 1.0e-5_dp
        type(material_t) :: m
        type(persson_t) :: r1, rs
        real(dp) :: h(n, n), q(2), qn, v(2), p1, p0, pc, sc, eloss, fc1(2), fcs(2), beta, cross
        complex(dp) :: es
        integer :: kq
        call paper_solid(ratio, m, error); if (allocated(error)) return
        beta = atan2(2.0_dp, 3.0_dp)
        q = two_pi/lcell*[3.0_dp, 2.0_dp]; qn = norm2(q)
        call cosine_surface(square_grid(h, lcell, lcell), h0, two_pi/qn, beta, h)
        v = [peak_speed(ratio, 3.6_dp), 0.0_dp]
        es = 1.0_dp/((1.0_dp - m%poisson**2)*m%compliance(dot_product(q, v)))
        eloss = aimag(es)
        p1 = qn*abs(es)*h0/2.0_dp
        p0 = 0.5_dp*p1
        pc = erf(p0/p1); sc = 0.5_dp + 0.5_dp*pc**2
        fc1 = -q*qn*h0**2*pc*eloss/4.0_dp
        fcs = sc*fc1
        call estimate(h, m, v, p0, r1, error); if (allocated(error)) return
        call estimate(h, m, v, p0, rs, error, s_correction=.true.); if (allocated(error)) return
        kq = minloc(abs(r1%q_per_m - qn), 1)
        cross = (r1%force_pa(1)*q(2) - r1%force_pa(2)*q(1))/(norm2(r1%force_pa)*qn)
        call report("P - erf(1/2)", r1%contact_area_fraction - pc)
        call report("rel. err F S=1", norm2(r1%force_pa - fc1)/norm2(fc1))
        call report("rel. err F S corr.", norm2(rs%force_pa - fcs)/norm2(fcs))
        call report("sin(F, q)", cross); call report("mu", r1%friction_coefficient)
        call check(error, r1%contact_area_fraction, pc, "P = erf(p0/p1)", rel=1.0e-13_dp); if (allocated(error)) return
        call check(error, r1%q_per_m(kq), qn, "the wave's shell", rel=1.0e-14_dp); if (allocated(error)) return
        call check(error, r1%area_fraction(kq), pc, "P at the wave's shell", rel=1.0e-13_dp); if (allocated(error)) return
        call check(error, norm2(r1%force_pa - fc1) <= 1.0e-12_dp*norm2(fc1), "F, S = 1"); if (allocated(error)) return
        call check(error, norm2(rs%force_pa - fcs) <= 1.0e-12_dp*norm2(fcs), "F, S corrected"); if (allocated(error)) return
        call check(error, abs(cross) <= 1.0e-12_dp, "F is not parallel to q"); if (allocated(error)) return
        call check(error, dot_product(r1%force_pa, q) < 0.0_dp, "F must point along -q"); if (allocated(error)) return
        call check(error, r1%friction_coefficient > 0.0_dp, "friction must resist"); if (allocated(error)) return
        call check(error, r1%lateral_force_ratio/r1%friction_coefficient, -tan(beta), "lateral/friction = -tan beta", &
                   rel=1.0e-12_dp)
    end subroutine test_single_wave

    !> Anisotropic surface (eps 0.5, alpha 30 deg), v at 20 deg, partial contact. Reversing v reverses F
    !> (mu and the lateral ratio unchanged); mirroring y -> -y with v mirrors F (lateral ratio changes
    !> sign); rotating surface and v by 90 deg rotates F. The transformed surfaces are exact permutations
    !> of the grid, so only summation order differs: 1e-12 relative to |F|.
    subroutine test_symmetries(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        real(dp), parameter :: p0 = 32.0e3_dp
        type(material_t) :: m
        type(persson_t) :: r, rr, rm, rt
        real(dp) :: h(n, n), hm(n, n), ht(n, n), v(2), fn, erv, erm, ert
        integer :: i, j
        call paper_rough(n, h, error, eps=0.5_dp, alpha=pi/6); if (allocated(error)) return
        call paper_solid(ratio, m, error); if (allocated(error)) return
        v = peak_speed(ratio, 4.0_dp)*[cos(pi/9), sin(pi/9)]
        do j = 1, n
            do i = 1, n
                hm(i, j) = h(i, mod(n - j + 1, n) + 1)     ! h(x, -y)
                ht(i, j) = h(j, mod(n - i + 1, n) + 1)     ! h(R^T x), R = rotation by +90 deg
            end do
        end do
        call estimate(h, m, v, p0, r, error); if (allocated(error)) return
        call estimate(h, m, -v, p0, rr, error); if (allocated(error)) return
        call estimate(hm, m, [v(1), -v(2)], p0, rm, error); if (allocated(error)) return
        call estimate(ht, m, [-v(2), v(1)], p0, rt, error); if (allocated(error)) return
        fn = norm2(r%force_pa)
        erv = norm2(rr%force_pa + r%force_pa)/fn
        erm = norm2(rm%force_pa - [r%force_pa(1), -r%force_pa(2)])/fn
        ert = norm2(rt%force_pa - [-r%force_pa(2), r%force_pa(1)])/fn
        call report("mu", r%friction_coefficient); call report("lateral", r%lateral_force_ratio)
        call report("reverse", erv); call report("mirror", erm); call report("rotate", ert)
        call check(error, abs(r%lateral_force_ratio) > 1.0e-3_dp*r%friction_coefficient, &
                   "the case must have a lateral force for the mirror test to mean anything")
        if (allocated(error)) return
        call check(error, erv <= 1.0e-12_dp, "reversed v: F(-v) /= -F(v)"); if (allocated(error)) return
        call check(error, erm <= 1.0e-12_dp, "mirror: F not mirrored"); if (allocated(error)) return
        call check(error, ert <= 1.0e-12_dp, "rotation: F not rotated"); if (allocated(error)) return
        call check(error, rm%lateral_force_ratio, -r%lateral_force_ratio, "mirror: lateral ratio", &
                   rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, rr%friction_coefficient, r%friction_coefficient, "reverse: mu", rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, rt%contact_area_fraction, r%contact_area_fraction, "rotation: area", rel=1.0e-13_dp)
    end subroutine test_symmetries

    !> Shells are the distinct |q| among the modes with power, whatever the rounding of |q|^2:
    !> square cell, (3,4) and (5,0) are one shell; the shell count equals the number of distinct integers
    !> i^2 + k^2 (counted here in integers), q_per_m = 2 pi sqrt(i^2 + k^2)/L, and P(q) equals a
    !> brute-force cumulative sum over those integer shells (elastic solid: |z|^2 = |q|^2 E*^2/4) to
    !> 1e-13. The same on a rectangular cell (64 x 32 cells, lx = 2 ly: distinct i^2 + 4 k^2) and on a
    !> long one (lx = 64 ly: i^2 + 4096 k^2; a row of modes then crowds into one or two buckets of the
    !> sort, up to 62 modes, which takes the radix path). A cell side perturbed by 1e-13 (keys no longer
    !> bitwise equal) gives the same shells and the same area to 1e-12.
    subroutine test_shells(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: young = 1.0e7_dp, p0 = 2.0e4_dp
        type(material_t) :: m
        type(persson_t) :: r, rp
        real(dp) :: h(64, 64), hr(64, 32), estar
        complex(dp), allocatable :: hk(:, :)
        call new_elastic(m, young, 0.5_dp, error); if (allocated(error)) return
        estar = young/0.75_dp
        call paper_rough(64, h, error); if (allocated(error)) return
        call spectrum(h, hk, error); if (allocated(error)) return
        call estimate_hk(64, 64, lcell, lcell, hk, m, [0.1_dp, 0.0_dp], p0, r, error)
        if (allocated(error)) return
        call against_integers(hk, 64, 1, lcell, estar, p0, r, "square", error); if (allocated(error)) return
        call estimate_hk(64, 64, lcell*(1.0_dp + 1.0e-13_dp), lcell, hk, m, [0.1_dp, 0.0_dp], p0, rp, error)
        if (allocated(error)) return
        call check(error, size(rp%q_per_m), size(r%q_per_m), "perturbed side: shell count"); if (allocated(error)) return
        call report("perturbed: max |dP|", maxval(abs(rp%area_fraction - r%area_fraction)))
        call check(error, maxval(abs(rp%area_fraction - r%area_fraction)) <= 1.0e-12_dp, "perturbed side: P(q)")
        if (allocated(error)) return
        hr = h(:, 1:64:2)      ! 64 x 32 cells (it has power on its Nyquist row)
        call spectrum(hr, hk, error); if (allocated(error)) return
        call estimate_hk(64, 32, 2.0_dp*lcell, lcell, hk, m, [0.1_dp, 0.05_dp], p0, r, error)
        if (allocated(error)) return
        call against_integers(hk, 64, 4, 2.0_dp*lcell, estar, p0, r, "rectangle", error); if (allocated(error)) return
        call estimate_hk(64, 32, 64.0_dp*lcell, lcell, hk, m, [0.1_dp, 0.05_dp], p0, r, error)
        if (allocated(error)) return
        call against_integers(hk, 64, 4096, 64.0_dp*lcell, estar, p0, r, "long cell", error)
    end subroutine test_shells

    !> Shells of `r` against the distinct integers s = (i-1)^2 + c kj^2 over the entries of hk with
    !> power, c = (lx/ly)^2 an integer, so |q| = 2 pi sqrt(s)/lx; and P(q) of an elastic solid against
    !> the cumulative sum over those integer shells of w |q|^2 E*^2/4 |a_q|^2 / (2 p0^2)
    subroutine against_integers(hk, nx, c, lx, estar, p0, r, label, error)
        complex(dp), intent(in) :: hk(:, :)
        integer, intent(in) :: nx, c
        real(dp), intent(in) :: lx, estar, p0
        type(persson_t), intent(in) :: r
        character(len=*), intent(in) :: label
        type(error_t), allocatable, intent(out) :: error
        real(dp), allocatable :: gsum(:)
        logical, allocatable :: seen(:)
        integer :: i, j, kj, ny, key, nshell, k
        real(dp) :: qerr, perr, cum, p, w
        ny = size(hk, 2)
        allocate (seen(0:(size(hk, 1) - 1)**2 + c*(ny/2)**2), gsum(0:(size(hk, 1) - 1)**2 + c*(ny/2)**2))
        seen = .false.; gsum = 0.0_dp
        do j = 1, ny
            kj = j - 1; if (kj > ny/2) kj = kj - ny
            do i = 1, size(hk, 1)
                if (i == 1 .and. j == 1) cycle
                if (.not. abs(hk(i, j))**2 > 0.0_dp) cycle
                key = (i - 1)**2 + c*kj**2
                w = merge(1.0_dp, 2.0_dp, i == 1 .or. i == nx/2 + 1)
                seen(key) = .true.
                gsum(key) = gsum(key) + w*(two_pi/lx)**2*key*estar**2/4.0_dp*abs(hk(i, j))**2
            end do
        end do
        nshell = count(seen)
        call check(error, size(r%q_per_m), nshell, label//": shell count"); if (allocated(error)) return
        qerr = 0.0_dp; perr = 0.0_dp; k = 0; cum = 0.0_dp
        do key = 0, size(seen) - 1
            if (.not. seen(key)) cycle
            k = k + 1
            cum = cum + gsum(key)
            p = erf(0.5_dp/sqrt(cum/(2.0_dp*p0**2)))
            qerr = max(qerr, abs(r%q_per_m(k) - two_pi*sqrt(real(key, dp))/lx)/r%q_per_m(k))
            perr = max(perr, abs(r%area_fraction(k) - p))
        end do
        call report(label//": max rel. err q", qerr); call report(label//": max |dP|", perr)
        call check(error, qerr <= 1.0e-14_dp, label//": q_per_m is not 2 pi sqrt(i^2 + c k^2)/lx")
        if (allocated(error)) return
        call check(error, perr <= 1.0e-13_dp, label//": P(q) differs from the brute-force shell sums")
    end subroutine against_integers

    !> Every kind of bad input returns an error whose message is prefix//"<variable> ..."
    !> (the grid, the velocity and the material come checked in the kernel)
    subroutine test_bad_input(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 16
        type(material_t) :: m
        type(kernel_t) :: k, k9
        type(persson_t) :: r
        type(error_t), allocatable :: err
        real(dp) :: h(n, n), nan
        complex(dp), allocatable :: hk(:, :), bad(:, :)
        type(grid_t) :: g9
        nan = ieee_value(1.0_dp, ieee_quiet_nan)
        call paper_rough(n, h, error); if (allocated(error)) return
        call spectrum(h, hk, error); if (allocated(error)) return
        call paper_solid(ratio, m, error); if (allocated(error)) return
        call new_kernel(k, square_grid(h, lcell, lcell), m, [1.0_dp, 0.0_dp], KERNEL_SPECTRAL, error)
        if (allocated(error)) return
        call persson_estimate(k, hk, 1.0e4_dp, r, err)
        call check(error, .not. allocated(err), "good input rejected"); if (allocated(error)) return
        call persson_estimate(k, hk, 0.0_dp, r, err)
        call expect(err, "p_mean_pa", error); if (allocated(error)) return
        call persson_estimate(k, hk, -1.0_dp, r, err)
        call expect(err, "p_mean_pa", error); if (allocated(error)) return
        call persson_estimate(k, hk, nan, r, err)
        call expect(err, "p_mean_pa", error); if (allocated(error)) return
        call persson_estimate(k, hk(:n/2, :), 1.0e4_dp, r, err)
        call expect(err, "hk", error); if (allocated(error)) return
        call new_grid(g9, n, n - 1, lcell, lcell, error); if (allocated(error)) return
        call new_kernel(k9, g9, m, [1.0_dp, 0.0_dp], KERNEL_SPECTRAL, error); if (allocated(error)) return
        call persson_estimate(k9, hk, 1.0e4_dp, r, err)
        call expect(err, "hk", error); if (allocated(error)) return
        bad = hk; bad(3, 4) = cmplx(0.0_dp, nan, dp)
        call persson_estimate(k, bad, 1.0e4_dp, r, err)
        call expect(err, "hk", error); if (allocated(error)) return
        call check(error, .not. allocated(r%q_per_m), "a failed estimate must leave the result at its defaults")
    end subroutine test_bad_input

    !> `err` must hold an error whose message starts prefix//name//" "
    subroutine expect(err, name, error)
        type(error_t), allocatable, intent(inout) :: err
        character(len=*), intent(in) :: name
        type(error_t), allocatable, intent(out) :: error
        if (.not. allocated(err)) then
            call check(error, .false., "no error for bad "//name); return
        end if
        call check(error, index(err%message, prefix//name//" ") == 1, &
                   "message does not start '"//prefix//name//" ': "//err%message)
        deallocate (err)
    end subroutine expect

    !> Expected failure: a zero pressure is an error, whose text the harness checks
    subroutine test_zero_pressure(error)
        type(error_t), allocatable, intent(out) :: error
        type(persson_t) :: r
        real(dp) :: h(16, 16)
        call estimate_zero(h, r, error)
    end subroutine test_zero_pressure

    subroutine estimate_zero(h, r, error)
        real(dp), intent(inout) :: h(:, :)
        type(persson_t), intent(out) :: r
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call paper_rough(size(h, 1), h, error); if (allocated(error)) return
        call paper_solid(ratio, m, error); if (allocated(error)) return
        call estimate(h, m, [1.0_dp, 0.0_dp], 0.0_dp, r, error)
    end subroutine estimate_zero

end module test_veslide_persson
