!> The bound-constrained CG (method 'bccg', the default for symmetric kernels): exact dense
!> reference, closed forms, agreement with Polonsky-Keer, warm start, refusal of a
!> non-symmetric kernel, and an iteration count that does not grow with the grid
module test_veslide_solver_bccg
    use veslide_kinds, only: dp
    use veslide_material, only: material_t
    use veslide_contact, only: contact_state_t
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: solve_case
    use reference_oracles, only: paper_rough, paper_solid, peak_speed, lcell
    use solver_fixture, only: dense_elastic, check_westergaard, check_full_contact_wave, compare_methods, &
                              check_warm_start, check_flat_iterations
    implicit none
    private
    public :: collect_solver_bccg

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
                         expect="&solver method = 'bccg' needs a symmetric operator") &
            ]
    end subroutine collect_solver_bccg

    subroutine test_dense_16(error)
        type(error_t), allocatable, intent(out) :: error
        call dense_elastic(16, 5.0e4_dp, error, method='bccg')
    end subroutine test_dense_16

    !> A few per cent of contact, where the preconditioner helps least
    subroutine test_dense_32(error)
        type(error_t), allocatable, intent(out) :: error
        call dense_elastic(32, 3.0e3_dp, error, method='bccg')
    end subroutine test_dense_32

    !> Westergaard (a profile: ny = 1) to the same bounds as Polonsky-Keer
    subroutine test_westergaard(error)
        type(error_t), allocatable, intent(out) :: error
        call check_westergaard(error, method='bccg')
    end subroutine test_westergaard

    !> A wave in full contact: p = p_mean + (E*|q|/2) h exactly
    subroutine test_full_contact_wave(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_state_t) :: s
        call check_full_contact_wave(s, error, method='bccg'); if (allocated(error)) return
        call report("iterations", real(s%iterations, dp))
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
        call compare_methods(h, lcell, 2.0e4_dp, 'pk', 'bccg', s, sb, error); if (allocated(error)) return
        call check(error, sb%operator_applications < s%operator_applications, "bccg not cheaper than pk")
    end subroutine test_matches_pk

    !> Starting from a converged solution costs (almost) nothing
    subroutine test_warm_start(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        real(dp) :: h(n, n)
        call paper_rough(n, h, error); if (allocated(error)) return
        call check_warm_start(h, lcell, 2.0e4_dp, error, method='bccg')
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
        call check_flat_iterations(2.0e4_dp, 'bccg', error)
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
