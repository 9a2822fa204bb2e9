!> The preconditioned splitting (method 'pdr'): exact dense references, exact full-contact forces,
!> agreement with the plain splitting, warm start from a pressure and its gap, an iteration count
!> that does not grow with the grid, and the choice 'auto' makes between pdr and dr
module test_veslide_solver_pdr
    use veslide_kinds, only: dp, pi
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_elastic, BASE_BONDED, BASE_FRICTIONLESS
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL, KERNEL_COLLOCATION
    use veslide_contact, only: contact_problem_t, contact_state_t
    use veslide_solver_options, only: solver_options_t, solver_method_names, SOLVER_PDR, SOLVER_DR, SOLVER_BCCG
    use veslide_solver, only: solve_contact, auto_method
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: case_problem
    use reference_oracles, only: paper_solid, peak_speed, lcell
    use solver_fixture, only: sliding_scene, relative_difference, dense_elastic, dense_sliding, &
                              check_full_contact_forces, compare_methods, check_flat_iterations
    implicit none
    private
    public :: collect_solver_pdr

contains

    subroutine collect_solver_pdr(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("dense-16-elastic", test_dense_16_elastic), &
            new_unittest("dense-32-visco-ratio-100", test_dense_32_visco), &
            new_unittest("dense-32-anisotropic-45", test_dense_32_aniso), &
            new_unittest("dense-32-layer-bonded-and-frictionless", test_dense_32_layer), &
            new_unittest("full-contact-forces-exact", test_full_contact_forces), &
            new_unittest("matches-dr", test_matches_dr), &
            new_unittest("warm-start-from-pressure-and-gap", test_warm_start), &
            new_unittest("anderson-mixing-and-relaxed-step-agree", test_mixing_agrees), &
            new_unittest("iterations-flat-in-the-grid", test_flat_iterations), &
            new_unittest("modulus-spread", test_spread), &
            new_unittest("auto-choice", test_auto) &
            ]
    end subroutine collect_solver_pdr


    subroutine test_dense_16_elastic(error)
        type(error_t), allocatable, intent(out) :: error
        call dense_elastic(16, 5.0e4_dp, error, method='pdr')
    end subroutine test_dense_16_elastic

    subroutine test_dense_32_visco(error)
        type(error_t), allocatable, intent(out) :: error
        call dense_sliding(error, method='pdr', ratio=100.0_dp)
    end subroutine test_dense_32_visco

    subroutine test_dense_32_aniso(error)
        type(error_t), allocatable, intent(out) :: error
        call dense_sliding(error, method='pdr', eps=0.3_dp, alpha=pi/4)
    end subroutine test_dense_32_aniso

    !> A viscoelastic layer (q0 d = 0.5, so the longest waves feel the base) on both bases, sliding:
    !> pdr against the dense exact solution of the same discrete (layered) problem
    subroutine test_dense_32_layer(error)
        type(error_t), allocatable, intent(out) :: error
        integer :: base
        do base = BASE_BONDED, BASE_FRICTIONLESS
            call dense_sliding(error, method='pdr', base=base); if (allocated(error)) return
        end do
    end subroutine test_dense_32_layer

    !> In full contact P(q) = H(q)/K(q): the forces in closed form, and pdr, which starts from that
    !> solution when it is admissible, confirms it within a few FFT pairs
    subroutine test_full_contact_forces(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_state_t) :: s
        call check_full_contact_forces(error, 'pdr', s); if (allocated(error)) return
        call report("FFT pairs", real(s%operator_applications, dp))
        call check(error, s%operator_applications <= 5, "the full-contact start was not taken")
    end subroutine test_full_contact_forces

    !> pdr and the plain splitting agree on a rough viscoelastic contact near the loss peak, and
    !> the work pdr reports covers its iterations (at least two FFT pairs each)
    subroutine test_matches_dr(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        type(material_t) :: m
        real(dp) :: h(n, n), v(2)
        type(contact_state_t) :: s, sd
        call sliding_scene(n, h, m, v, error); if (allocated(error)) return
        call compare_methods(h, lcell, 3.2e4_dp, 'pdr', 'dr', s, sd, error, mat=m, velocity=v)
        if (allocated(error)) return
        call check(error, s%operator_applications >= 2*s%iterations, "fewer than two FFT pairs per iteration")
    end subroutine test_matches_dr

    !> Started from a converged pressure and its gap (a sweep's warm start), pdr stops at once
    subroutine test_warm_start(error)
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(contact_problem_t) :: problem
        type(solver_options_t) :: opts
        type(contact_state_t) :: s, sw
        call pdr_rough_64(problem, k, fft, opts, s, error); if (allocated(error)) return
        call solve_contact(problem, fft, opts, sw, error, p_init=s%p, g_init=s%g); if (allocated(error)) return
        call report("cold", real(s%iterations, dp)); call report("warm", real(sw%iterations, dp))
        call check(error, sw%converged .and. sw%iterations <= 2 .and. s%iterations > 10, "warm start did not help")
    end subroutine test_warm_start

    !> The over-relaxed plain step (the default) and Anderson mixing (anderson_memory = 5) reach
    !> the same pressure, and the kernel's multiplier the solve borrowed comes back unchanged
    subroutine test_mixing_agrees(error)
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(contact_problem_t) :: problem
        type(solver_options_t) :: opts
        type(contact_state_t) :: s, sa
        call pdr_rough_64(problem, k, fft, opts, s, error); if (allocated(error)) return
        opts%anderson_memory = 5
        call solve_contact(problem, fft, opts, sa, error); if (allocated(error)) return
        call report("relaxed FFT pairs", real(s%operator_applications, dp))
        call report("Anderson FFT pairs", real(sa%operator_applications, dp))
        call report("max |dp|/max p", relative_difference(sa%p, s%p))
        call check(error, s%converged .and. sa%converged, "not converged"); if (allocated(error)) return
        call check(error, relative_difference(sa%p, s%p) <= 1.0e-9_dp, "pressures differ")
        if (allocated(error)) return
        call check(error, all(problem%kernel%multiplier(1.0_dp) == k%multiplier(1.0_dp)), &
                   "the kernel's multiplier changed")
    end subroutine test_mixing_agrees

    !> The sliding scene on 64^2 cells, pressed to 32 kPa: the problem, its kernel `k` (a copy the
    !> problem's can be compared with), the transforms, and its cold solve `s` by pdr with the
    !> default options `opts` (but the method)
    subroutine pdr_rough_64(problem, k, fft, opts, s, error)
        type(contact_problem_t), intent(out) :: problem
        type(kernel_t), intent(out) :: k
        type(fft2d_t), intent(out) :: fft
        type(solver_options_t), intent(out) :: opts
        type(contact_state_t), intent(out) :: s
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 64
        type(material_t) :: m
        real(dp) :: h(n, n), v(2)
        call sliding_scene(n, h, m, v, error); if (allocated(error)) return
        call case_problem(h, lcell, lcell, 3.2e4_dp, m, v, problem, error, kernel=k, fft=fft)
        if (allocated(error)) return
        opts%method = SOLVER_PDR
        call solve_contact(problem, fft, opts, s, error)
    end subroutine pdr_rough_64

    !> The same spectrum on 64^2 .. 256^2 (q0 .. 16 q0), ratio 11 near the loss peak, tolerance
    !> 1e-8: pdr's FFT pairs grow by at most 1.5 from the coarsest grid to the finest
    subroutine test_flat_iterations(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call check_flat_iterations(3.2e4_dp, 'pdr', error, mat=m, velocity=[peak_speed(11.0_dp, 4.0_dp), 0.0_dp])
    end subroutine test_flat_iterations

    !> The anisotropy measure behind 'auto': 1 for an elastic solid (spectral kernel); for a
    !> one-term solid far above the loss peak, Einf/E0 (glassy along v, rubbery across it)
    subroutine test_spread(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(kernel_t) :: k
        type(grid_t) :: grid
        call new_grid(grid, 64, 64, lcell, lcell, error); if (allocated(error)) return
        call new_elastic(m, 1.0e7_dp, 0.3_dp, error); if (allocated(error)) return
        call new_kernel(k, grid, m, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error); if (allocated(error)) return
        call report("elastic", k%modulus_spread())
        call check(error, k%modulus_spread(), 1.0_dp, "elastic spread", rel=1.0e-12_dp); if (allocated(error)) return
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call new_kernel(k, grid, m, [1.0e3_dp, 0.0_dp], KERNEL_SPECTRAL, error); if (allocated(error)) return
        call report("ratio 11 at v tau/L0 = 1e3", k%modulus_spread())
        call check(error, k%modulus_spread(), 11.0_dp, "glassy/rubbery spread", rel=1.0e-3_dp)
    end subroutine test_spread

    !> 'auto': bccg when symmetric; pdr from 512^2 for a moderately anisotropic operator; dr on
    !> smaller grids and for strongly anisotropic operators (ratio 1000 in motion)
    subroutine test_auto(error)
        type(error_t), allocatable, intent(out) :: error
        call expect(512, 11.0_dp, peak_speed(11.0_dp, 8.0_dp), KERNEL_SPECTRAL, SOLVER_PDR, error)
        if (allocated(error)) return
        call expect(512, 11.0_dp, peak_speed(11.0_dp, 8.0_dp), KERNEL_COLLOCATION, SOLVER_PDR, error)
        if (allocated(error)) return
        call expect(256, 11.0_dp, peak_speed(11.0_dp, 8.0_dp), KERNEL_SPECTRAL, SOLVER_PDR, error)
        if (allocated(error)) return
        call expect(128, 11.0_dp, peak_speed(11.0_dp, 8.0_dp), KERNEL_SPECTRAL, SOLVER_DR, error)
        if (allocated(error)) return
        call expect(512, 1000.0_dp, peak_speed(1000.0_dp, 8.0_dp), KERNEL_SPECTRAL, SOLVER_DR, error)
        if (allocated(error)) return
        call expect(512, 1000.0_dp, 0.0_dp, KERNEL_SPECTRAL, SOLVER_BCCG, error)
    contains
        subroutine expect(n, ratio, speed, variant, method, error)
            integer, intent(in) :: n, variant, method
            real(dp), intent(in) :: ratio, speed
            type(error_t), allocatable, intent(out) :: error
            type(material_t) :: m
            type(contact_problem_t) :: problem
            real(dp), allocatable :: h(:, :)
            allocate (h(n, n)); h = 0.0_dp
            call paper_solid(ratio, m, error); if (allocated(error)) return
            call case_problem(h, lcell, lcell, 1.0e4_dp, m, [speed, 0.0_dp], problem, error, variant=variant)
            if (allocated(error)) return
            call check(error, auto_method(problem) == method, "auto takes '"// &
                       trim(solver_method_names(auto_method(problem)))//"', expected '"// &
                       trim(solver_method_names(method))//"'")
        end subroutine expect
    end subroutine test_auto

end module test_veslide_solver_pdr
