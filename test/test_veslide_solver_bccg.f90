!> The bound-constrained CG (method 'bccg', the default for symmetric kernels): exact dense
!> reference, closed forms, agreement with Polonsky-Keer, warm start, refusal of a
!> non-symmetric kernel, and an iteration count that does not grow with the grid
module test_veslide_solver_bccg
    use veslide_kinds, only: dp, i8, two_pi
    use veslide_grid, only: grid_t, new_grid
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t
    use veslide_contact, only: contact_state_t
    use veslide_surface, only: psd_t, random_surface, cosine_surface
    use veslide_analysis, only: contact_area_fraction, mean_separation
    use testsuite, only: error_t, unittest_t, new_unittest, check, rel_error, report
    use test_support, only: solve_case, square_grid
    use dense_reference, only: influence_matrix, solve_dense, dense_compare
    use reference_oracles, only: westergaard_t, westergaard, paper_rough, paper_solid, peak_speed, lcell
    implicit none
    private
    public :: collect_solver_bccg, fixed_spectrum_surface

contains

    subroutine collect_solver_bccg(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("dense-16-elastic", test_dense_16), &
            new_unittest("dense-32-elastic-small-contact", test_dense_32), &
            new_unittest("westergaard", test_westergaard), &
            new_unittest("full-contact-wave", test_full_contact_wave), &
            new_unittest("matches-pk", test_matches_pk), &
            new_unittest("warm-start", test_warm_start), &
            new_unittest("auto-takes-bccg-when-symmetric", test_auto), &
            new_unittest("iterations-flat-in-the-grid", test_flat_iterations), &
            new_unittest("non-symmetric-kernel-refused", test_refuse, should_fail=.true., &
                         expect="method 'bccg' needs a symmetric") &
            ]
    end subroutine collect_solver_bccg

    !> The same self-affine surface (spectrum q0 .. kcut q0, H = 0.8, rms slope 0.025, seed 11) on
    !> any n^2 grid that resolves it
    subroutine fixed_spectrum_surface(n, kcut, h, error)
        integer, intent(in) :: n
        real(dp), intent(in) :: kcut
        real(dp), allocatable, intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(psd_t) :: psd
        type(grid_t) :: grid
        real(dp) :: q0
        q0 = two_pi/lcell
        psd = psd_t(hurst=0.8_dp, q_low=q0, q_roll=q0, q_cut=kcut*q0)
        allocate (h(n, n))
        call new_grid(grid, n, n, lcell, lcell, error); if (allocated(error)) return
        call random_surface(grid, psd, 11_i8, 0.025_dp, 0.0_dp, h, error)
    end subroutine fixed_spectrum_surface

    !> bccg on an elastic solid (E = 10 MPa, nu = 0.5) against the dense solution
    subroutine dense_elastic(h, p_mean, error)
        real(dp), intent(in) :: h(:, :), p_mean
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        call dense_compare(h, m, [0.0_dp, 0.0_dp], p_mean, error, method='bccg')
    end subroutine dense_elastic

    subroutine test_dense_16(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(16, 16)
        call paper_rough(16, h, error); if (allocated(error)) return
        call dense_elastic(h, 5.0e4_dp, error)
    end subroutine test_dense_16

    !> A few per cent of contact, where the preconditioner helps least
    subroutine test_dense_32(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(32, 32)
        call paper_rough(32, h, error); if (allocated(error)) return
        call dense_elastic(h, 3.0e3_dp, error)
    end subroutine test_dense_32

    !> Westergaard (a profile: ny = 1) to the same bounds as Polonsky-Keer
    subroutine test_westergaard(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 1024
        real(dp), parameter :: l = 1.0_dp, h0 = 1.0e-3_dp, estar = 1.0e6_dp, p = 1000.0_dp
        real(dp) :: h(n, 1)
        type(contact_state_t) :: s
        type(westergaard_t) :: w
        call cosine_surface(square_grid(h, l, l), h0, l, 0.0_dp, h)
        call solve_case(h, l, l, p, s, error, estar=estar, method='bccg'); if (allocated(error)) return
        w = westergaard(p, h0, l, estar)
        call report("width error [cells]", abs(contact_area_fraction(s%p) - w%width_fraction)*n)
        call report("peak", rel_error(maxval(s%p), w%peak_pa)); call report("gap", rel_error(mean_separation(s%g), &
                                                                                               w%mean_gap_m))
        call check(error, abs(contact_area_fraction(s%p) - w%width_fraction) <= 2.0_dp/n, "contact width")
        if (allocated(error)) return
        call check(error, maxval(s%p), w%peak_pa, "peak pressure", rel=5.0e-6_dp); if (allocated(error)) return
        call check(error, mean_separation(s%g), w%mean_gap_m, "mean gap", rel=2.0e-5_dp)
    end subroutine test_westergaard

    !> A wave in full contact: p = p_mean + (E*|q|/2) h exactly
    subroutine test_full_contact_wave(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        real(dp), parameter :: l = 1.0_dp, h0 = 1.0e-4_dp, estar = 1.0e6_dp
        real(dp) :: h(n, n), lam, th, amp, p_mean
        type(contact_state_t) :: s
        lam = l/sqrt(13.0_dp); th = atan2(2.0_dp, 3.0_dp)
        call cosine_surface(square_grid(h, l, l), h0, lam, th, h)
        amp = 0.5_dp*estar*two_pi/lam*h0
        p_mean = 1.5_dp*amp
        call solve_case(h, l, l, p_mean, s, error, estar=estar, method='bccg'); if (allocated(error)) return
        call report("max |p - exact|/p*", maxval(abs(s%p - (p_mean + amp*h/h0)))/amp)
        call report("iterations", real(s%iterations, dp))
        call check(error, maxval(abs(s%p - (p_mean + amp*h/h0)))/amp <= 1.0e-10_dp, "pressure")
        if (allocated(error)) return
        ! the preconditioner is the exact inverse in full contact: one step
        call check(error, s%iterations <= 2, "more than two iterations in full contact")
    end subroutine test_full_contact_wave

    !> BCCG and Polonsky-Keer agree on a rough elastic contact; BCCG needs fewer FFT pairs
    subroutine test_matches_pk(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 128
        real(dp) :: h(n, n)
        type(contact_state_t) :: s, sb
        call paper_rough(n, h, error); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 2.0e4_dp, s, error, method='pk'); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 2.0e4_dp, sb, error, method='bccg'); if (allocated(error)) return
        call report("pk FFT pairs", real(s%operator_applications, dp))
        call report("bccg FFT pairs", real(sb%operator_applications, dp))
        call report("max |dp|/max p", maxval(abs(s%p - sb%p))/maxval(s%p))
        call check(error, maxval(abs(s%p - sb%p))/maxval(s%p) <= 1.0e-9_dp, "pressures differ")
        if (allocated(error)) return
        call check(error, sb%operator_applications < s%operator_applications, "bccg not cheaper than pk")
    end subroutine test_matches_pk

    !> Starting from a converged solution costs (almost) nothing
    subroutine test_warm_start(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        real(dp) :: h(n, n)
        type(contact_state_t) :: s, sw
        call paper_rough(n, h, error); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 2.0e4_dp, s, error, method='bccg'); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 2.0e4_dp, sw, error, method='bccg', p_init=s%p); if (allocated(error)) return
        call report("cold", real(s%iterations, dp)); call report("warm", real(sw%iterations, dp))
        call check(error, sw%iterations <= 2 .and. s%iterations > 10, "warm start did not help")
    end subroutine test_warm_start

    subroutine test_auto(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(32, 32)
        type(contact_state_t) :: s
        call paper_rough(32, h, error); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 2.0e4_dp, s, error); if (allocated(error)) return
        call check(error, s%method == 'bccg', "auto took "//s%method)
    end subroutine test_auto

    !> The same surface on 64^2 .. 256^2 (spectrum q0 .. 16 q0), tolerance 1e-8: the FFT pairs
    !> grow by at most 1.5 from the coarsest to the finest (Polonsky-Keer: about 2x per doubling)
    subroutine test_flat_iterations(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), allocatable :: h(:, :)
        type(contact_state_t) :: s
        integer :: k, n, pairs(3)
        do k = 1, 3
            n = 32*2**k
            call fixed_spectrum_surface(n, 16.0_dp, h, error); if (allocated(error)) return
            call solve_case(h, lcell, lcell, 2.0e4_dp, s, error, tol=1.0e-8_dp, method='bccg')
            if (allocated(error)) return
            pairs(k) = s%operator_applications
        end do
        call report("FFT pairs 64^2", real(pairs(1), dp)); call report("128^2", real(pairs(2), dp))
        call report("256^2", real(pairs(3), dp))
        call check(error, pairs(3) <= 1.5_dp*pairs(1), "FFT pairs grow with the grid")
    end subroutine test_flat_iterations

    subroutine test_refuse(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(contact_state_t) :: s
        real(dp) :: h(16, 16)
        call paper_rough(16, h, error); if (allocated(error)) return
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 3.0e4_dp, s, error, mat=m, velocity=[peak_speed(11.0_dp, 2.0_dp), 0.0_dp], &
                        method='bccg')
    end subroutine test_refuse

end module test_veslide_solver_bccg
