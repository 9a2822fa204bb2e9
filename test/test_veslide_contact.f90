!> The contact problem and its one residual definition; the quantities derived from a solution
module test_veslide_contact
    use veslide_kinds, only: dp, pi
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t
    use veslide_contact, only: contact_problem_t, contact_state_t
    use veslide_analysis, only: contact_area_fraction, contact_area_subcell, slope_force
    use veslide_quantities, only: results_t, add_force_quantities, axial_of, AXIAL_NONE, AXIAL_HALF_TURN, &
                                  AXIAL_SYMMETRIC
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: solve_case, case_problem, square_grid
    use veslide_surface, only: cosine_surface, paraboloid_surface, bisinusoid_surface
    use reference_oracles, only: paper_solid, peak_speed, westergaard, westergaard_t
    use solver_fixture, only: solve_full_contact
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
        tests = [new_unittest("slope-force-exact-in-full-contact", test_slope_force), &
                 new_unittest("subcell-area-exact-edges-second-order", test_area_synthetic), &
                 new_unittest("subcell-area-westergaard-quarter-cell", test_area_westergaard), &
                 new_unittest("subcell-area-hertz-within-0.3-percent", test_area_hertz), &
                 new_unittest("subcell-area-bisinusoid-ten-times-closer-than-count", test_area_bisinusoid)]
    end subroutine collect_analysis

    subroutine elastic_problem(h, problem, error)
        real(dp), intent(in) :: h(:, :)
        type(contact_problem_t), intent(out) :: problem
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call new_elastic(m, 1.0e6_dp, 0.0_dp, error); if (allocated(error)) return
        call case_problem(h, 1.0_dp, 1.0_dp, 10.0_dp, m, [0.0_dp, 0.0_dp], problem, error)
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
        call solve_full_contact(h, m, [peak_speed(11.0_dp, 2.0_dp), 0.0_dp], 5.0e6_dp, f, s, k, fft, error)
        if (allocated(error)) return
        call slope_force(k%grid, fft, s%p, h, fs)
        call report("rel. difference", maxval(abs(f - fs))/maxval(abs(f)))
        call check(error, maxval(abs(f - fs)) <= 1.0e-9_dp*maxval(abs(f)), "slope force differs in full contact")
    end subroutine test_slope_force

    !> Westergaard (exact width), n = 256 .. 2048: the sub-cell edge is on average within a
    !> quarter of a cell, less than half the cell count's error (measured 0.23 and 0.63 cells: the
    !> discrete solution's own edge, not the estimator, now limits the area: docs/validation.md)
    subroutine test_area_westergaard(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: l = 1.0_dp, h0 = 1.0e-3_dp, estar = 1.0e6_dp, p = 1000.0_dp
        integer, parameter :: nlev = 4
        real(dp) :: ecount(nlev), esub(nlev), w
        real(dp), allocatable :: h(:, :)
        type(contact_state_t) :: s
        type(westergaard_t) :: ref
        integer :: k, n
        ref = westergaard(p, h0, l, estar)
        do k = 1, nlev
            n = 256*2**(k - 1)
            allocate (h(n, 1))
            call cosine_surface(square_grid(h, l, l), h0, l, 0.0_dp, h)
            call solve_case(h, l, l, p, s, error, estar=estar); if (allocated(error)) return
            w = ref%width_fraction
            ecount(k) = abs(contact_area_fraction(s%p) - w)*n       ! in cells
            esub(k) = abs(contact_area_subcell(s%p, s%g) - w)*n
            deallocate (h)
        end do
        call report("cell count: mean error [cells]", sum(ecount)/nlev)
        call report("sub-cell: mean error [cells]", sum(esub)/nlev)
        call check(error, sum(esub)/nlev <= 0.3_dp .and. sum(esub) <= 0.5_dp*sum(ecount), &
                   "sub-cell edge not within a quarter of a cell, or not twice as good as counting")
    end subroutine test_area_westergaard

    !> Hertz contact of a paraboloid, radius a = L/16, on 64^2 .. 512^2 (a = 4 .. 32 cells): the
    !> sub-cell area is within 0.3 % of pi a^2 at every resolution (measured 0.1 %; the cell count
    !> is 13 % off at 64^2 and 1 % at 512^2)
    subroutine test_area_hertz(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: r = 0.1_dp, estar = 1.0e6_dp, l = 1.0e-2_dp
        integer, parameter :: nlev = 4
        real(dp) :: acount(nlev), asub(nlev), a, f, exact
        real(dp), allocatable :: h(:, :)
        type(contact_state_t) :: s
        integer :: k, n
        a = l/16.0_dp
        f = 4.0_dp*estar*a**3/(3.0_dp*r)
        exact = pi*(a/l)**2
        do k = 1, nlev
            n = 64*2**(k - 1)
            allocate (h(n, n))
            call paraboloid_surface(square_grid(h, l, l), r, h)
            call solve_case(h, l, l, f/l**2, s, error, estar=estar); if (allocated(error)) return
            acount(k) = contact_area_fraction(s%p); asub(k) = contact_area_subcell(s%p, s%g)
            deallocate (h)
        end do
        call report("cell count: largest error", maxval(abs(acount/exact - 1)))
        call report("sub-cell: largest error", maxval(abs(asub/exact - 1)))
        call check(error, maxval(abs(asub/exact - 1)) <= 3.0e-3_dp, "sub-cell area against Hertz")
    end subroutine test_area_hertz

    !> Bisinusoid at p/p* = 0.1 (two patches, curved edges), 128^2 .. 512^2 against a 1024^2
    !> solve: the sub-cell area is at least ten times closer to it than the cell count. Neither is
    !> second order on the solver's fields (their successive changes do not fall steadily): the
    !> sub-cell estimate misplaces the edge by at most 0.03 cell, the count by 0.1-0.2 cell
    !> (docs/validation.md)
    subroutine test_area_bisinusoid(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: l = 1.0_dp, d = 1.0e-3_dp, estar = 1.0e6_dp
        integer, parameter :: nlev = 3
        real(dp) :: acount(nlev), asub(nlev), pstar, aref
        real(dp), allocatable :: h(:, :)
        type(contact_state_t) :: s
        integer :: k, n
        pstar = sqrt(2.0_dp)*pi*estar*d/l
        do k = 1, nlev + 1
            n = 128*2**(k - 1)
            allocate (h(n, n))
            call bisinusoid_surface(square_grid(h, l, l), d, l, h)
            call solve_case(h, l, l, 0.1_dp*pstar, s, error, estar=estar); if (allocated(error)) return
            if (k <= nlev) then
                acount(k) = contact_area_fraction(s%p); asub(k) = contact_area_subcell(s%p, s%g)
            else
                aref = contact_area_subcell(s%p, s%g)
            end if
            deallocate (h)
        end do
        call report("cell count: sum of |A - A_1024|", sum(abs(acount - aref)))
        call report("sub-cell: sum of |A - A_1024|", sum(abs(asub - aref)))
        call check(error, sum(abs(asub - aref)) <= 0.1_dp*sum(abs(acount - aref)), &
                   "sub-cell area not ten times closer to the 1024^2 solve than the cell count")
    end subroutine test_area_bisinusoid

    !> Fields with the exact asymptotics of a smooth edge (p^2 and g^(2/3) exactly quadratic
    !> across it): a strip is measured exactly, a disc to second order (the polygon through the
    !> crossings): order >= 1.9 over 32^2 .. 512^2 against pi R^2
    subroutine test_area_synthetic(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: nlev = 5
        real(dp), allocatable :: p(:, :), g(:, :)
        real(dp) :: x, y, r, e(nlev), rad
        integer :: n, i, j, k
        n = 64
        allocate (p(n, 1), g(n, 1))
        do i = 1, n
            x = (i - 0.5_dp)/n - 0.5_dp
            p(i, 1) = sqrt(max(0.0_dp, 1.0_dp - (x/0.3_dp)**2)); g(i, 1) = max(0.0_dp, abs(x) - 0.3_dp)**1.5_dp
        end do
        call report("strip error", abs(contact_area_subcell(p, g) - 0.6_dp))
        call check(error, contact_area_subcell(p, g), 0.6_dp, "strip", abs=1.0e-12_dp); if (allocated(error)) return
        deallocate (p, g)
        rad = 0.2_dp
        do k = 1, nlev
            n = 32*2**(k - 1)
            allocate (p(n, n), g(n, n))
            do j = 1, n
                do i = 1, n
                    x = (i - 0.5_dp)/n - 0.5_dp; y = (j - 0.5_dp)/n - 0.5_dp; r = sqrt(x*x + y*y)
                    p(i, j) = sqrt(max(0.0_dp, 1.0_dp - (r/rad)**2)); g(i, j) = max(0.0_dp, r - rad)**1.5_dp
                end do
            end do
            e(k) = abs(contact_area_subcell(p, g) - pi*rad**2)/(pi*rad**2)
            deallocate (p, g)
        end do
        call report("disc: finest", e(nlev)); call report("its order", order(e))
        call check(error, order(e) >= 1.9_dp, "disc area is not second order")
    end subroutine test_area_synthetic

    !> Least-squares slope of -log2(e) against the refinement level (e halves per level: order 1)
    pure real(dp) function order(e) result(q)
        real(dp), intent(in) :: e(:)
        real(dp) :: x(size(e)), y(size(e))
        integer :: k
        x = [(real(k, dp), k = 1, size(e))]
        y = -log(e)/log(2.0_dp)
        q = sum((x - sum(x)/size(x))*(y - sum(y)/size(y)))/sum((x - sum(x)/size(x))**2)
    end function order

end module test_veslide_contact
