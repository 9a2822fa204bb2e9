!> The contact problem and its one residual definition; the quantities derived from a solution
module test_veslide_contact
    use veslide_kinds, only: dp
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use veslide_contact, only: contact_problem_t, contact_state_t, new_contact_problem
    use veslide_analysis, only: contact_area_fraction, slope_force
    use veslide_quantities, only: results_t, add_force_quantities, axial_of, AXIAL_NONE, AXIAL_HALF_TURN, &
                                  AXIAL_SYMMETRIC
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: solve_case, square_grid
    use reference_oracles, only: paper_solid, peak_speed, lcell
    implicit none
    private
    public :: collect_contact, collect_quantities, collect_analysis

contains

    subroutine collect_contact(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("residual-measures-by-hand", test_residuals), &
            new_unittest("flat-surface-height-scale", test_flat_scale), &
            new_unittest("nan-heights-refused", test_nan, should_fail=.true., expect="the heights contain NaN") &
            ]
    end subroutine collect_contact

    subroutine collect_quantities(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("friction-and-lateral-conventions", test_force_conventions), &
            new_unittest("axial-quantities", test_axial) &
            ]
    end subroutine collect_quantities

    subroutine collect_analysis(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [new_unittest("slope-force-exact-in-full-contact", test_slope_force)]
    end subroutine collect_analysis

    subroutine elastic_problem(h, problem, error)
        real(dp), intent(in) :: h(:, :)
        type(contact_problem_t), intent(out) :: problem
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(kernel_t) :: k
        call new_elastic(m, 1.0e6_dp, 0.0_dp, error); if (allocated(error)) return
        call new_kernel(k, square_grid(h, 1.0_dp, 1.0_dp), m, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error)
        if (allocated(error)) return
        call new_contact_problem(problem, k, h, 10.0_dp, error)
    end subroutine elastic_problem

    !> A 2 x 2 candidate whose four measures are computed by hand
    subroutine test_residuals(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_problem_t) :: problem
        type(contact_state_t) :: s
        real(dp) :: h(2, 2), hs
        h = reshape([1.0_dp, -1.0_dp, -1.0_dp, 1.0_dp], [2, 2])*1.0e-6_dp      ! mean 0, rms 1e-6
        call elastic_problem(h, problem, error); if (allocated(error)) return
        hs = 1.0e-6_dp
        call check(error, problem%height_scale_m, hs, "h_s is the rms height", rel=1.0e-15_dp); if (allocated(error)) return
        call problem%start(s)
        s%p = reshape([30.0_dp, -2.0_dp, 0.0_dp, 12.0_dp], [2, 2])
        s%u = reshape([1.5_dp, 0.0_dp, -2.0_dp, 1.0_dp], [2, 2])*1.0e-6_dp
        call problem%residuals(s)
        ! g0 = u - h = (0.5, 1, -1, 0) e-6; contact set p > 0: cells 1, 4, mean g0 0.25e-6, so d = -0.25e-6
        ! and g = (0.25, 0.75, -1.25, -0.25) e-6
        call check(error, s%approach_m, -0.25e-6_dp, "approach", rel=1.0e-12_dp); if (allocated(error)) return
        call check(error, s%penetration, 1.25_dp, "penetration", rel=1.0e-12_dp); if (allocated(error)) return
        ! sum p g = (30*0.25 - 2*0.75 + 0 - 12*0.25) e-6 = 3e-6; sum |p| = 44
        call check(error, s%complementarity, 3.0_dp/44.0_dp, "complementarity", rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, s%negative_pressure, 0.2_dp, "negative pressure", rel=1.0e-12_dp); if (allocated(error)) return
        call check(error, s%load_error, 0.0_dp, "load error", abs=1.0e-15_dp); if (allocated(error)) return
        call check(error, s%residual, 1.25_dp, "residual is the largest measure", rel=1.0e-12_dp)
    end subroutine test_residuals

    !> A flat surface has no height scale: the displacement scale p_mean max|K| takes its place
    subroutine test_flat_scale(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_problem_t) :: problem
        real(dp) :: h(8, 8)
        h = 3.0_dp
        call elastic_problem(h, problem, error); if (allocated(error)) return
        call check(error, problem%height_scale_m, 10.0_dp*problem%kernel%max_abs(), "scale", rel=1.0e-15_dp)
    end subroutine test_flat_scale

    subroutine test_nan(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_problem_t) :: problem
        real(dp) :: h(4, 4), zero
        zero = 0
        h = 0; h(2, 3) = zero/zero
        call elastic_problem(h, problem, error)
    end subroutine test_nan

    !> v at 120 degrees, F chosen along -v plus a part 90 degrees counter-clockwise from v
    subroutine test_force_conventions(error)
        type(error_t), allocatable, intent(out) :: error
        type(results_t) :: r
        real(dp) :: vhat(2), lat(2), f(2)
        vhat = [cos(120.0_dp*acos(-1.0_dp)/180), sin(120.0_dp*acos(-1.0_dp)/180)]
        lat = [-vhat(2), vhat(1)]
        f = -3.0_dp*vhat + 0.5_dp*lat
        call add_force_quantities(r, f, f, 2.0_dp*vhat, 120.0_dp, 100.0_dp)
        call check(error, r%get('friction_coefficient'), 0.03_dp, "friction = -F.v_hat/p", rel=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, r%get('lateral_force_ratio'), 0.005_dp, "lateral = F.(z x v_hat)/p", rel=1.0e-13_dp)
        if (allocated(error)) return
        call check(error, r%get('dissipated_power_w_m2'), 6.0_dp, "dissipation = -F.v", rel=1.0e-14_dp)
    end subroutine test_force_conventions

    subroutine test_axial(error)
        type(error_t), allocatable, intent(out) :: error
        call check(error, axial_of('theta_d_rad') == AXIAL_HALF_TURN .and. axial_of('phi_rad') == AXIAL_SYMMETRIC &
                   .and. axial_of('friction_coefficient') == AXIAL_NONE, "axial kinds")
    end subroutine test_axial

    !> In full contact grad w = grad h everywhere, so the slope estimator <p grad h> equals the
    !> exact force <p grad w> of the discrete operator to round-off
    subroutine test_slope_force(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 32
        type(material_t) :: m
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(contact_state_t) :: s
        real(dp) :: h(n, n), f(2), fs(2)
        integer :: i, j
        do j = 1, n
            do i = 1, n
                h(i, j) = 1.0e-6_dp*(cos(2*acos(-1.0_dp)*(2*i + j)/n) + 0.3_dp*sin(2*acos(-1.0_dp)*(i - 3*j)/n))
            end do
        end do
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call solve_case(h, lcell, lcell, 5.0e6_dp, s, error, mat=m, velocity=[peak_speed(11.0_dp, 2.0_dp), 0.0_dp], &
                        kernel=k)
        if (allocated(error)) return
        call check(error, contact_area_fraction(s%p), 1.0_dp, "not in full contact", abs=0.0_dp)
        if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        f = k%tangential_force(fft, s%p)
        call slope_force(k%grid, fft, s%p, h, fs)
        call report("rel. difference", maxval(abs(f - fs))/maxval(abs(f)))
        call check(error, maxval(abs(f - fs)) <= 1.0e-9_dp*maxval(abs(f)), "slope force differs in full contact")
    end subroutine test_slope_force

end module test_veslide_contact
