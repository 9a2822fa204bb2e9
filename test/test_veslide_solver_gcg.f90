!> The adhesive contact laws and their solver ('gcg', conjugate gradients on the gap): Johnson's
!> JKR wave, the hard-wall limit, the laws' maps
module test_veslide_solver_gcg
    use veslide_kinds, only: dp, pi, two_pi
    use veslide_fftw, only: fft2d_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use veslide_contact, only: contact_problem_t, contact_state_t, new_contact_problem
    use veslide_contact_law, only: contact_law_t, new_adhesive_law, LAW_EXPONENTIAL, LAW_DUGDALE, ADH_STRESS
    use veslide_solver_options, only: solver_options_t, solver_method_id
    use veslide_solver, only: solve_contact
    use veslide_strings, only: str
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_solver_gcg

    !> Johnson's wave: wavelength, amplitude [m], contact modulus [Pa] (nu = 0: E* = E)
    real(dp), parameter :: lambda = 1.0e-4_dp, amp = 1.0e-6_dp, estar = 1.0e7_dp

contains

    subroutine collect_solver_gcg(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("law-maps", test_law_maps), &
            new_unittest("jkr-wave-johnson-1995", test_jkr_wave) &
            ]
    end subroutine collect_solver_gcg

    !> The laws' attraction is the derivative of their energy, which integrates to w
    subroutine test_law_maps(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law
        real(dp) :: g(3, 1), e1(3, 1), e2(3, 1), s(3, 1), dg
        law = new_adhesive_law(LAW_EXPONENTIAL, 0.05_dp, 2.0e-9_dp)
        call check(error, law%param(ADH_STRESS) == 0.05_dp/2.0e-9_dp, "sigma0 = w/rho"); if (allocated(error)) return
        g(:, 1) = [0.0_dp, 1.0e-9_dp, 5.0e-9_dp]
        dg = 1.0e-13_dp
        e1 = law%energy(g + dg); e2 = law%energy(g + 2*dg)
        s = law%attraction(g + 1.5_dp*dg)
        call check(error, maxval(abs((e2 - e1)/dg - s)/law%param(ADH_STRESS)) < 1.0e-5_dp, &
                   "exponential: sigma = dV/dg"); if (allocated(error)) return
        e1 = law%energy(0.0_dp*g)
        call check(error, all(abs(e1 + 0.05_dp) <= 4.0e-16_dp*0.05_dp), &
                   "exponential: V(0) = -w"); if (allocated(error)) return
        law = new_adhesive_law(LAW_DUGDALE, 0.05_dp, 2.0e-9_dp)
        s = law%attraction(g)
        call check(error, all(s(:, 1) == [2.5e7_dp, 2.5e7_dp, 0.0_dp]), "dugdale: sigma0 within rho, 0 beyond")
        if (allocated(error)) return
        e1 = law%energy(g)
        call check(error, all(abs(e1(:, 1) - [-0.05_dp, -0.025_dp, 0.0_dp]) <= 1.0e-17_dp), "dugdale: V")
    end subroutine test_law_maps

    !> Johnson (1995): a rigid wave h cos(2 pi x/lambda) on an elastic half-space with adhesion
    !> (alpha = 0.2, exponential law of range h/64, 4096 cells), under load control along the
    !> unloading branch p/p* = 0.4, 0.25, 0.1, 0, -0.03 (p* = pi E* h/lambda), each load
    !> warm-started from the last: the contact half-width a obeys
    !> p/p* = sin^2(pi a) - alpha sqrt(tan(pi a)) (a in wavelengths) within 5e-3
    subroutine test_jkr_wave(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 4096
        real(dp), parameter :: alpha = 0.2_dp, loads(5) = [0.4_dp, 0.25_dp, 0.1_dp, 0.0_dp, -0.03_dp]
        real(dp) :: h(n, 1), x, w, rho, pstar, a, jkr, worst
        real(dp), allocatable :: gap(:, :)
        type(grid_t) :: grid
        type(material_t) :: mat
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(contact_problem_t) :: problem
        type(contact_state_t) :: state
        type(solver_options_t) :: opts
        type(contact_law_t) :: law
        integer :: i, m
        character(len=120) :: line
        do i = 1, n
            x = (i - 1)*lambda/n
            h(i, 1) = amp*cos(two_pi*x/lambda)
        end do
        pstar = pi*estar*amp/lambda
        w = alpha**2*pi**2*estar*amp**2/(2*lambda)
        rho = amp/64
        law = new_adhesive_law(LAW_EXPONENTIAL, w, rho)
        call new_elastic(mat, estar, 0.0_dp, error); if (allocated(error)) return
        call new_grid(grid, n, 1, lambda, lambda/n, error); if (allocated(error)) return
        call new_kernel(k, grid, mat, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error); if (allocated(error)) return
        call fft%init(n, 1, error, planner='estimate'); if (allocated(error)) return
        opts%method = solver_method_id('gcg')
        opts%tolerance = 1.0e-10_dp
        worst = 0.0_dp
        do m = 1, size(loads)
            call new_contact_problem(problem, k, h, loads(m)*pstar, error, law=law); if (allocated(error)) return
            if (allocated(gap)) then
                call solve_contact(problem, fft, opts, state, error, g_init=gap)
            else
                call solve_contact(problem, fft, opts, state, error)
            end if
            if (allocated(error)) return
            call check(error, state%converged, "converged at p/p* = "//str(loads(m)))
            if (allocated(error)) return
            a = count(state%g <= 0.0_dp)/real(n, dp)/2
            jkr = sin(pi*a)**2 - alpha*sqrt(tan(pi*a))
            write (line, '(a,f6.3,a,f8.5,a,i0,a,i0,a)') "p/p*=", loads(m), " (a=", a, ", its ", state%iterations, &
                ", pairs ", state%operator_applications, "): deviation"
            call report(trim(line), loads(m) - jkr)
            worst = max(worst, abs(loads(m) - jkr))
            gap = state%g
        end do
        call check(error, worst <= 5.0e-3_dp, "JKR wave within 5e-3 p*")
    end subroutine test_jkr_wave

end module test_veslide_solver_gcg
