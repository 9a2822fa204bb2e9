!> Surface generator: statistics against the spectrum, Parseval, reproducibility, grid invariance
module test_veslide_surface
    use veslide_kinds, only: dp, i8, pi, two_pi
    use veslide_error, only: error_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_spectrum, only: slope_tensor
    use veslide_surface, only: psd_t, psd_value, random_surface, random_coefficients, rms_height, &
                               expected_slope_tensor
    use veslide_material, only: material_t, new_one_term
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use reference_oracles, only: full_contact_force
    use testsuite, only: unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_surface

contains

    function grid_of(nx, ny, lx, ly) result(grid)
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: lx, ly
        type(grid_t) :: grid
        type(error_t), allocatable :: error
        call new_grid(grid, nx, ny, lx, ly, error)
    end function grid_of

    subroutine collect_surface(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("normalised-power-exponential", test_power_exponential), &
            new_unittest("neighbouring-coefficients-independent", test_neighbours), &
            new_unittest("coefficients-are-the-surface", test_coefficients_surface), &
            new_unittest("gaussian-heights-512", test_gaussian_heights), &
            new_unittest("cross-slope-over-seeds", test_cross_slope_seeds), &
            new_unittest("full-contact-lateral-force-over-seeds", test_lateral_force_seeds), &
            new_unittest("parseval-and-targets", test_parseval), &
            new_unittest("slope-tensor-statistics", test_slope_statistics), &
            new_unittest("same-surface-finer-grid", test_grid_invariance), &
            new_unittest("bad-hurst", test_bad_hurst, should_fail=.true., expect="hurst must be in (0, 1)") &
            ]
    end subroutine collect_surface




    !> Normalised power r = |a_q|^2/<|a_q|^2> of every drawn mode in the band (the ki > 0 half:
    !> one independent draw each), for an isotropic 256^2 surface with k_cut = 64
    subroutine band_powers(seed, r, kx, ky, z)
        integer(i8), intent(in) :: seed
        real(dp), allocatable, intent(out) :: r(:)
        integer, allocatable, intent(out) :: kx(:), ky(:)
        !> the real part of a_q in units of its standard deviation
        real(dp), allocatable, intent(out) :: z(:)
        integer, parameter :: n = 256
        complex(dp) :: ak(n/2 + 1, n)
        type(psd_t) :: psd
        real(dp) :: v, sl, sig2
        integer :: i, j, m
        psd = psd_t(hurst=0.8_dp, q_low=two_pi, q_roll=two_pi, q_cut=64*two_pi)
        call random_coefficients(grid_of(n, n, 1.0_dp, 1.0_dp), psd, seed, ak, v, sl)
        allocate (r(n*n), kx(n*n), ky(n*n), z(n*n))
        m = 0
        do j = 1, n
            do i = 2, n/2 + 1
                if (abs(ak(i, j)) == 0.0_dp) cycle
                m = m + 1
                kx(m) = i - 1; ky(m) = merge(j - 1 - n, j - 1, j - 1 > n/2)
                sig2 = 0.5_dp*two_pi**2*psd_value(psd, two_pi*kx(m), two_pi*ky(m))
                r(m) = abs(ak(i, j))**2/(2*sig2)
                z(m) = real(ak(i, j), dp)/sqrt(sig2)
            end do
        end do
        r = r(1:m); kx = kx(1:m); ky = ky(1:m); z = z(1:m)
    end subroutine band_powers

    !> The normalised power follows the exponential law (coefficient of variation 1, Kolmogorov-
    !> Smirnov distance below the 1 % critical value) over the band AND within every k_x column:
    !> a generator that reuses an amplitude down a column has a column variation of 0
    subroutine test_power_exponential(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), allocatable :: r(:), z(:), rc(:)
        integer, allocatable :: kx(:), ky(:)
        real(dp) :: cv, d, cv_col, worst_col
        integer :: s, k, ncol
        do s = 1, 3
            call band_powers(int(s, i8), r, kx, ky, z)
            cv = sqrt(sum((r - sum(r)/size(r))**2)/(size(r) - 1))/(sum(r)/size(r))
            d = ks_exponential(r)
            if (s == 1) then
                call report("modes", real(size(r), dp)); call report("band CV", cv); call report("KS distance", d)
            end if
            ! CV of an exponential sample of N: sd about sqrt(2/N) for the variance, so 1 +- 0.05 at N = 6000
            call check(error, abs(cv - 1.0_dp) < 0.1_dp, "band coefficient of variation"); if (allocated(error)) return
            call check(error, d < 1.63_dp/sqrt(real(size(r), dp)), "KS distance to Exp(1)"); if (allocated(error)) return
            cv_col = 0; ncol = 0; worst_col = huge(1.0_dp)
            do k = 1, 64
                rc = pack(r, kx == k)
                if (size(rc) < 30) cycle
                ncol = ncol + 1
                cv = sqrt(sum((rc - sum(rc)/size(rc))**2)/(size(rc) - 1))/(sum(rc)/size(rc))
                cv_col = cv_col + cv; worst_col = min(worst_col, cv)
            end do
            cv_col = cv_col/ncol
            if (s == 1) then
                call report("mean column CV", cv_col); call report("smallest column CV", worst_col)
            end if
            call check(error, abs(cv_col - 1.0_dp) < 0.1_dp, "mean CV within k_x columns"); if (allocated(error)) return
            call check(error, worst_col > 0.4_dp, "a k_x column with too little spread"); if (allocated(error)) return
        end do
    end subroutine test_power_exponential

    !> Kolmogorov-Smirnov distance of a sample to the Exp(1) law
    function ks_exponential(x) result(d)
        real(dp), intent(in) :: x(:)
        real(dp) :: d, y(size(x)), f
        integer :: k, n
        n = size(x)
        y = x
        call sort(y)
        d = 0
        do k = 1, n
            f = 1 - exp(-y(k))
            d = max(d, abs(f - real(k, dp)/n), abs(f - real(k - 1, dp)/n))
        end do
    end function ks_exponential

    !> Heap sort, ascending
    subroutine sort(a)
        real(dp), intent(inout) :: a(:)
        integer :: n, i, last
        real(dp) :: t
        n = size(a)
        do i = n/2, 1, -1
            call sift(i, n)
        end do
        do last = n, 2, -1
            t = a(1); a(1) = a(last); a(last) = t
            call sift(1, last - 1)
        end do
    contains
        subroutine sift(start, bottom)
            integer, intent(in) :: start, bottom
            integer :: root, child
            real(dp) :: tt
            root = start
            do while (2*root <= bottom)
                child = 2*root
                if (child < bottom) then
                    if (a(child + 1) > a(child)) child = child + 1
                end if
                if (a(root) >= a(child)) return
                tt = a(root); a(root) = a(child); a(child) = tt
                root = child
            end do
        end subroutine sift
    end subroutine sort

    !> Neighbouring coefficients (q and q + e_x, q and q + e_y) are uncorrelated in power and in
    !> real part: |correlation| below 4/sqrt(N) (N pairs)
    subroutine test_neighbours(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), allocatable :: r(:), z(:)
        integer, allocatable :: kx(:), ky(:), pos(:, :)
        real(dp) :: c(4)
        integer :: m, k, d
        call band_powers(7_i8, r, kx, ky, z)
        allocate (pos(0:200, -200:200)); pos = 0
        do k = 1, size(r)
            pos(kx(k), ky(k)) = k
        end do
        do d = 1, 2
            block
                real(dp), allocatable :: a(:), b(:), za(:), zb(:)
                integer :: nb
                allocate (a(size(r)), b(size(r)), za(size(r)), zb(size(r)))
                nb = 0
                do k = 1, size(r)
                    m = pos(kx(k) + merge(1, 0, d == 1), ky(k) + merge(1, 0, d == 2))
                    if (m == 0) cycle
                    nb = nb + 1
                    a(nb) = r(k); b(nb) = r(m); za(nb) = z(k); zb(nb) = z(m)
                end do
                c(2*d - 1) = correlation(a(1:nb), b(1:nb))
                c(2*d) = correlation(za(1:nb), zb(1:nb))
                call report(merge("power corr. x", "power corr. y", d == 1), c(2*d - 1))
                call report(merge("Re corr. x", "Re corr. y", d == 1), c(2*d))
                call check(error, all(abs(c(2*d - 1:2*d)) < 4/sqrt(real(nb, dp))), "neighbours correlated")
                if (allocated(error)) return
            end block
        end do
    end subroutine test_neighbours

    pure real(dp) function correlation(a, b) result(c)
        real(dp), intent(in) :: a(:), b(:)
        real(dp) :: ma, mb
        ma = sum(a)/size(a); mb = sum(b)/size(b)
        c = sum((a - ma)*(b - mb))/sqrt(sum((a - ma)**2)*sum((b - mb)**2))
    end function correlation

    !> The heights are the transform of the drawn coefficients (to round-off), scaled once
    subroutine test_coefficients_surface(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        type(fft2d_t) :: fft
        type(psd_t) :: psd
        complex(dp) :: ak(n/2 + 1, n)
        real(dp) :: h(n, n), v, sl, scale
        psd = psd_t(hurst=0.6_dp, eccentricity=0.5_dp, alpha_rad=0.4_dp, q_low=two_pi, q_roll=two_pi, q_cut=20*two_pi)
        call random_coefficients(grid_of(n, n, 1.0_dp, 1.0_dp), psd, 21_i8, ak, v, sl)
        call random_surface(grid_of(n, n, 1.0_dp, 1.0_dp), psd, 21_i8, 0.0_dp, 1.0_dp, h, error, realised=.false.)
        if (allocated(error)) return
        scale = 1.0_dp/sqrt(v)
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        fft%x = h; call fft%forward()
        call report("max |H/N^2 - s a|/max|s a|", maxval(abs(fft%k/real(n*n, dp) - scale*ak))/maxval(abs(scale*ak)))
        call check(error, maxval(abs(fft%k/real(n*n, dp) - scale*ak)) <= 1.0e-13_dp*maxval(abs(scale*ak)), &
                   "heights are not the transform of the coefficients")
    end subroutine test_coefficients_surface

    !> Heights of a random surface are Gaussian: skewness and excess kurtosis of a 512^2 surface with
    !> a flat band spectrum (k = 1..128, many modes of equal weight, correlation length ~2 cells)
    subroutine test_gaussian_heights(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 512
        real(dp), allocatable :: h(:, :)
        type(psd_t) :: psd
        real(dp) :: m2, m3, m4, skew, kurt, neff
        allocate (h(n, n))
        psd = psd_t(hurst=0.8_dp, q_low=two_pi, q_roll=128*two_pi, q_cut=128*two_pi)   ! flat: C constant
        call random_surface(grid_of(n, n, 1.0_dp, 1.0_dp), psd, 4_i8, 0.0_dp, 1.0_dp, h, error); if (allocated(error)) return
        m2 = sum(h**2)/size(h); m3 = sum(h**3)/size(h); m4 = sum(h**4)/size(h)
        skew = m3/m2**1.5_dp; kurt = m4/m2**2 - 3
        ! independent samples: about one per (n/(2*128))^2 cells, i.e. (2*128)^2 over the cell
        neff = (2*128.0_dp)**2*0.785_dp
        call report("skewness", skew); call report("excess kurtosis", kurt)
        call check(error, abs(skew) < 5*sqrt(6/neff), "skewness"); if (allocated(error)) return
        call check(error, abs(kurt) < 5*sqrt(24/neff), "excess kurtosis")
    end subroutine test_gaussian_heights

    !> Sample mean and variance of x over seeds against the expectation of a weighted sum of
    !> independent exponentials X = sum c_k E_k (E_k of mean mu_k): mean sum c_k mu_k, variance
    !> sum c_k^2 mu_k^2, fourth cumulant 6 sum c_k^4 mu_k^4 (sets the error of the sample variance)
    subroutine check_seed_spread(error, what, x, mean_e, var_e, kappa4)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in) :: what
        real(dp), intent(in) :: x(:), mean_e, var_e, kappa4
        real(dp) :: mean, var, se_ratio
        integer :: n
        n = size(x)
        mean = sum(x)/n; var = sum((x - mean)**2)/(n - 1)
        se_ratio = sqrt(kappa4/var_e**2/n + 2.0_dp/(n - 1))
        call report(what//" mean/sd", (mean - mean_e)/sqrt(var_e))
        call report(what//" var/expected", var/var_e); call report("its standard error", se_ratio)
        call check(error, abs(mean - mean_e) < 4*sqrt(var_e/n), what//": mean over seeds"); if (allocated(error)) return
        call check(error, abs(var/var_e - 1) < 4*se_ratio, what//": spread over seeds")
    end subroutine check_seed_spread

    !> Realised cross slope m11 = <h_x h_y> of an isotropic surface over 400 seeds: zero mean and the
    !> spread of its expectation (a generator with one amplitude per k_x column gives m11 = 0 exactly)
    subroutine test_cross_slope_seeds(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 32, nseed = 400
        type(fft2d_t) :: fft
        type(psd_t) :: psd
        complex(dp) :: ak(n/2 + 1, n)
        real(dp) :: h(n, n), m(2, 2), x(nseed), v, sl, q(2), mu, c, var_e, k4, s4
        integer :: s, i, j
        type(grid_t) :: g
        g = grid_of(n, n, 1.0_dp, 1.0_dp)
        psd = psd_t(hurst=0.8_dp, q_low=two_pi, q_roll=two_pi, q_cut=12*two_pi)
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        do s = 1, nseed
            call random_surface(grid_of(n, n, 1.0_dp, 1.0_dp), psd, int(s, i8), 0.0_dp, 1.0_dp, h, error, realised=.false.)
            if (allocated(error)) return
            call slope_tensor(grid_of(n, n, 1.0_dp, 1.0_dp), fft, h, m)
            x(s) = m(1, 2)
        end do
        ! m11 = s^2 sum_{ki > 0} 2 qx qy |a_q|^2, s = 1/sqrt(var): |a_q|^2 exponential of mean 2 sig^2
        call random_coefficients(grid_of(n, n, 1.0_dp, 1.0_dp), psd, 1_i8, ak, v, sl)
        s4 = 1.0_dp/v**2
        var_e = 0; k4 = 0
        do j = 1, n
            do i = 2, n/2
                q = g%wavevector(i, j)
                if (j == n/2 + 1) cycle
                mu = two_pi**2*psd_value(psd, q(1), q(2))
                c = 2*q(1)*q(2)
                var_e = var_e + c**2*mu**2; k4 = k4 + 6*c**4*mu**4
            end do
        end do
        call check_seed_spread(error, "m11", x, 0.0_dp, s4*var_e, s4**2*k4)
    end subroutine test_cross_slope_seeds

    !> Exact full-contact lateral force of an anisotropic surface (eps = 0.5) at alpha = 0, sliding
    !> along x near the loss peak, over 400 seeds: zero mean, spread of its expectation. In full
    !> contact F = -(1/N^4) sum_q q Im K |H/K|^2 for any surface (docs/validation.md).
    subroutine test_lateral_force_seeds(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 32, nseed = 400
        real(dp), parameter :: l = 0.01_dp
        type(fft2d_t) :: fft
        type(psd_t) :: psd
        type(material_t) :: mat
        type(kernel_t) :: k
        complex(dp) :: ak(n/2 + 1, n)
        real(dp) :: h(n, n), x(nseed), v, sl, q(2), mu, c, var_e, k4, s4, fxy(2)
        integer :: s, i, j
        psd = psd_t(hurst=0.8_dp, eccentricity=0.5_dp, q_low=two_pi/l, q_roll=two_pi/l, q_cut=12*two_pi/l)
        call new_one_term(mat, 1.0e8_dp, 11.0_dp, 0.01_dp, 0.5_dp, error); if (allocated(error)) return
        call new_kernel(k, grid_of(n, n, l, l), mat, [0.05_dp, 0.0_dp], KERNEL_SPECTRAL, error); if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        do s = 1, nseed
            call random_surface(grid_of(n, n, l, l), psd, int(s, i8), 0.0_dp, 1.0e-5_dp, h, error, realised=.false.)
            if (allocated(error)) return
            fxy = full_contact_force(k, fft, h)
            x(s) = fxy(2)
        end do
        ! F_y = s^2 sum_{ki > 0} c_q |a_q|^2 with c_q = -2 qy Im K/|K|^2 (the ki = 0 column has Im K = 0)
        call random_coefficients(grid_of(n, n, l, l), psd, 1_i8, ak, v, sl)
        s4 = (1.0e-5_dp)**4/v**2
        var_e = 0; k4 = 0
        do j = 1, n
            do i = 2, n/2
                if (j == n/2 + 1) cycle
                q = k%grid%wavevector(i, j)
                mu = two_pi**2/l**2*psd_value(psd, q(1), q(2))
                c = -2*q(2)*aimag(k%value(i, j))/abs(k%value(i, j))**2
                var_e = var_e + c**2*mu**2; k4 = k4 + 6*c**4*mu**4
            end do
        end do
        call check_seed_spread(error, "F_y", x, 0.0_dp, s4*var_e, s4**2*k4)
    end subroutine test_lateral_force_seeds

    !> Parseval: slope tensor from spectral derivatives equals the finite sum in real space of the
    !> exact trigonometric derivative; and the normalisation targets are met exactly
    subroutine test_parseval(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 128
        type(fft2d_t) :: fft
        type(psd_t) :: psd
        real(dp) :: h(n, n), m(2, 2), var_spec
        integer :: i, j
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        psd = psd_t(hurst=0.7_dp, eccentricity=0.6_dp, alpha_rad=0.3_dp, q_low=two_pi, q_roll=2*two_pi, q_cut=40*two_pi)
        call random_surface(grid_of(n, n, 1.0_dp, 1.0_dp), psd, 3_i8, 0.025_dp, 0.0_dp, h, error); if (allocated(error)) return
        call slope_tensor(grid_of(n, n, 1.0_dp, 1.0_dp), fft, h, m)
        call check(error, sqrt(m(1, 1) + m(2, 2)), 0.025_dp, "realised rms slope", rel=1.0e-12_dp)
        if (allocated(error)) return
        ! Parseval for the heights: variance = sum |H_q|^2 / N^2
        fft%x = h; call fft%forward()
        var_spec = 0
        do j = 1, n
            do i = 1, n/2 + 1
                var_spec = var_spec + merge(1.0_dp, 2.0_dp, i == 1 .or. i == n/2 + 1)*abs(fft%k(i, j))**2
            end do
        end do
        var_spec = var_spec/real(n, dp)**4
        call report("parseval", abs(var_spec - rms_height(h)**2)/rms_height(h)**2)
        call check(error, var_spec, rms_height(h)**2, "Parseval", rel=1.0e-12_dp); if (allocated(error)) return
        call check(error, abs(sum(h))/size(h) <= 1.0e-15_dp*rms_height(h)*size(h), "zero mean")
        if (allocated(error)) return
        call random_surface(grid_of(n, n, 1.0_dp, 1.0_dp), psd, 3_i8, 0.0_dp, 2.0e-6_dp, h, error); if (allocated(error)) return
        call check(error, rms_height(h), 2.0e-6_dp, "realised rms height", rel=1.0e-12_dp)
    end subroutine test_parseval

    !> Over 16 seeds the slope tensor matches the spectrum's expectation (gamma_s, theta_s = alpha)
    !> within sampling error; and for the power-law spectrum gamma_s is close to eps^2.
    subroutine test_slope_statistics(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 128, nseed = 16
        type(fft2d_t) :: fft
        type(psd_t) :: psd
        real(dp) :: h(n, n), m(2, 2), me(2, 2), var, g(nseed), th(nseed), ge, the, sg, sth
        integer :: s
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        psd = psd_t(hurst=0.8_dp, eccentricity=0.6_dp, alpha_rad=pi/6, q_low=two_pi, q_roll=two_pi, q_cut=32*two_pi)
        do s = 1, nseed
            call random_surface(grid_of(n, n, 1.0_dp, 1.0_dp), psd, int(s, i8), 0.025_dp, 0.0_dp, h, error, realised=.false.)
            if (allocated(error)) return
            call slope_tensor(grid_of(n, n, 1.0_dp, 1.0_dp), fft, h, m)
            call ratio_angle(m, g(s), th(s))
        end do
        call expected_slope_tensor(grid_of(n, n, 1.0_dp, 1.0_dp), psd, me, var)
        call ratio_angle(me, ge, the)
        sg = sqrt(sum((g - sum(g)/nseed)**2)/(nseed - 1))/sqrt(real(nseed, dp))
        sth = sqrt(sum((th - sum(th)/nseed)**2)/(nseed - 1))/sqrt(real(nseed, dp))
        call report("gamma mean", sum(g)/nseed); call report("gamma expected", ge); call report("eps^2", 0.36_dp)
        call report("theta mean", sum(th)/nseed); call report("alpha", pi/6)
        call check(error, abs(sum(g)/nseed - ge) < 4*sg, "gamma_s vs expectation"); if (allocated(error)) return
        call check(error, abs(sum(th)/nseed - the) < 4*sth, "theta_s vs expectation"); if (allocated(error)) return
        call report("expected theta - alpha", the - pi/6)
        ! the square lattice of the lowest modes (|q| = q0, sqrt(2) q0, ...) is not rotation
        ! invariant: the expected tensor of the discrete spectrum turns from alpha by -0.013 rad
        ! here (-0.0049 at 1024^2 with k_cut = 256: it vanishes slowly with more modes)
        call check(error, abs(the - pi/6) < 2.0e-2_dp, "expected tensor points along alpha"); if (allocated(error)) return
        ! the cut-offs are circles in q, not ellipses, so gamma is not exactly eps^2: measured
        ! 0.408 for eps^2 = 0.36 (H = 0.8, band q0..32 q0); see docs/validation.md
        call check(error, ge, 0.36_dp, "expected gamma vs eps^2", rel=0.15_dp)
    end subroutine test_slope_statistics

    pure subroutine ratio_angle(m, gam, theta)
        real(dp), intent(in) :: m(2, 2)
        real(dp), intent(out) :: gam, theta
        real(dp) :: tr, dif, l1, l2
        tr = m(1, 1) + m(2, 2); dif = sqrt((m(1, 1) - m(2, 2))**2 + 4*m(1, 2)**2)
        l1 = 0.5_dp*(tr + dif); l2 = 0.5_dp*(tr - dif)
        gam = l2/l1
        theta = 0.5_dp*atan2(2*m(1, 2), m(1, 1) - m(2, 2))
    end subroutine ratio_angle

    !> The same seed and spectrum on a grid twice as fine gives the same surface, sampled finer
    subroutine test_grid_invariance(error)
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: f1, f2
        type(psd_t) :: psd
        real(dp) :: h1(64, 64), h2(128, 128)
        call f1%init(64, 64, error, planner='estimate'); if (allocated(error)) return
        call f2%init(128, 128, error, planner='estimate'); if (allocated(error)) return
        psd = psd_t(hurst=0.8_dp, eccentricity=0.5_dp, alpha_rad=1.0_dp, q_low=two_pi, q_roll=two_pi, q_cut=20*two_pi)
        call random_surface(grid_of(64, 64, 1.0_dp, 1.0_dp), psd, 9_i8, 0.0_dp, 1.0_dp, h1, error, realised=.false.)
        if (allocated(error)) return
        call random_surface(grid_of(128, 128, 1.0_dp, 1.0_dp), psd, 9_i8, 0.0_dp, 1.0_dp, h2, error, realised=.false.)
        if (allocated(error)) return
        call report("max difference", maxval(abs(h2(1::2, 1::2) - h1)))
        call check(error, maxval(abs(h2(1::2, 1::2) - h1)) <= 1.0e-12_dp, "surfaces differ")
    end subroutine test_grid_invariance

    subroutine test_bad_hurst(error)
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: fft
        real(dp) :: h(8, 8)
        call fft%init(8, 8, error, planner='estimate'); if (allocated(error)) return
        call random_surface(grid_of(8, 8, 1.0_dp, 1.0_dp), psd_t(hurst=1.5_dp, q_low=1.0_dp, q_roll=1.0_dp, q_cut=10.0_dp), &
                            1_i8, 0.01_dp, 0.0_dp, h, error)
    end subroutine test_bad_hurst

end module test_veslide_surface
