!> Surface generator: statistics against the spectrum, Parseval, reproducibility, grid invariance
module test_veslide_surface
    use veslide_kinds, only: dp, i8, pi, two_pi
    use veslide_fftw, only: fft2d_t
    use veslide_surface, only: psd_t, random_surface, slope_tensor, rms_height, expected_slope_tensor
    use veslide_rng, only: rng_t, normal_pair_at
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_surface

contains

    subroutine collect_surface(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("rng-reproducible", test_rng), &
            new_unittest("rng-normal-moments", test_rng_moments), &
            new_unittest("parseval-and-targets", test_parseval), &
            new_unittest("slope-tensor-statistics", test_slope_statistics), &
            new_unittest("same-surface-finer-grid", test_grid_invariance), &
            new_unittest("bad-hurst", test_bad_hurst, should_fail=.true.) &
            ]
    end subroutine collect_surface

    subroutine test_rng(error)
        type(error_t), allocatable, intent(out) :: error
        type(rng_t) :: a, b, c
        integer :: k
        real(dp) :: z1, z2, y1, y2
        call a%seed(42_i8); call b%seed(42_i8); call c%seed(43_i8)
        do k = 1, 1000
            if (a%uniform() /= b%uniform()) then
                call check(error, .false., "same seed, different stream"); return
            end if
        end do
        call check(error, a%uniform() /= c%uniform(), "different seeds, same number"); if (allocated(error)) return
        call normal_pair_at(5_i8, 3, -2, z1, z2)
        call normal_pair_at(6_i8, 7, 1, y1, y2)       ! an unrelated call in between changes nothing
        call normal_pair_at(5_i8, 3, -2, y1, y2)
        call check(error, z1 == y1 .and. z2 == y2, "counter-based draw not reproducible")
    end subroutine test_rng

    !> Mean, variance and kurtosis of 2e5 counter-based normals within 5 standard errors
    subroutine test_rng_moments(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 100000
        real(dp) :: s1, s2, s4, z1, z2
        integer :: k
        s1 = 0; s2 = 0; s4 = 0
        do k = 1, n
            call normal_pair_at(11_i8, k, -k, z1, z2)
            s1 = s1 + z1 + z2; s2 = s2 + z1**2 + z2**2; s4 = s4 + z1**4 + z2**4
        end do
        s1 = s1/(2*n); s2 = s2/(2*n); s4 = s4/(2*n)
        call report("mean", s1); call report("var-1", s2 - 1); call report("m4-3", s4 - 3)
        ! standard errors: mean 1/sqrt(N), variance sqrt(2/N), 4th moment sqrt(96/N)
        call check(error, abs(s1) < 5/sqrt(2.0_dp*n), "mean"); if (allocated(error)) return
        call check(error, abs(s2 - 1) < 5*sqrt(2.0_dp/(2*n)), "variance"); if (allocated(error)) return
        call check(error, abs(s4 - 3) < 5*sqrt(96.0_dp/(2*n)), "fourth moment")
    end subroutine test_rng_moments

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
        call random_surface(fft, 1.0_dp, 1.0_dp, psd, 3_i8, 0.025_dp, 0.0_dp, h, error); if (allocated(error)) return
        call slope_tensor(fft, 1.0_dp, 1.0_dp, h, m)
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
        call random_surface(fft, 1.0_dp, 1.0_dp, psd, 3_i8, 0.0_dp, 2.0e-6_dp, h, error); if (allocated(error)) return
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
            call random_surface(fft, 1.0_dp, 1.0_dp, psd, int(s, i8), 0.025_dp, 0.0_dp, h, error, realised=.false.)
            if (allocated(error)) return
            call slope_tensor(fft, 1.0_dp, 1.0_dp, h, m)
            call ratio_angle(m, g(s), th(s))
        end do
        call expected_slope_tensor(n, n, 1.0_dp, 1.0_dp, psd, me, var)
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
        call random_surface(f1, 1.0_dp, 1.0_dp, psd, 9_i8, 0.0_dp, 1.0_dp, h1, error, realised=.false.)
        if (allocated(error)) return
        call random_surface(f2, 1.0_dp, 1.0_dp, psd, 9_i8, 0.0_dp, 1.0_dp, h2, error, realised=.false.)
        if (allocated(error)) return
        call report("max difference", maxval(abs(h2(1::2, 1::2) - h1)))
        call check(error, maxval(abs(h2(1::2, 1::2) - h1)) <= 1.0e-12_dp, "surfaces differ")
    end subroutine test_grid_invariance

    subroutine test_bad_hurst(error)
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: fft
        real(dp) :: h(8, 8)
        call fft%init(8, 8, error, planner='estimate'); if (allocated(error)) return
        call random_surface(fft, 1.0_dp, 1.0_dp, psd_t(hurst=1.5_dp, q_low=1.0_dp, q_roll=1.0_dp, q_cut=10.0_dp), &
                            1_i8, 0.01_dp, 0.0_dp, h, error)
    end subroutine test_bad_hurst

end module test_veslide_surface
