!> The solver suites' common ground: the scenes they solve (the paper's rough surface under its
!> sliding solid, one spectrum on any grid, a wave in full contact, Westergaard's profile) and the
!> checks they make of a solver named by its method ('auto' where it is absent): against the dense
!> reference, the closed-form full-contact forces and pressure, Westergaard, another method, a warm
!> start, and the growth of the work with the grid
module solver_fixture
    use veslide_kinds, only: dp, i8, pi, two_pi
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t
    use veslide_contact, only: contact_state_t
    use veslide_surface, only: psd_t, random_surface, cosine_surface
    use veslide_analysis, only: contact_area_fraction, mean_separation
    use testsuite, only: error_t, check, rel_error, report
    use test_support, only: solve_case, square_grid
    use dense_reference, only: dense_compare
    use reference_oracles, only: westergaard_t, westergaard, paper_rough, paper_solid, peak_speed, &
                                 full_contact_force, lcell
    implicit none
    private
    public :: sliding_scene, fixed_spectrum_surface, mirrored, rotated, relative_difference, &
              dense_elastic, dense_sliding, solve_full_contact, check_full_contact_forces, &
              check_full_contact_wave, wave_h0, westergaard_errors, check_westergaard, compare_methods, &
              check_warm_start, check_flat_iterations

    !> Amplitude of the full-contact wave of check_full_contact_wave [m]
    real(dp), parameter :: wave_h0 = 1.0e-4_dp

contains

    !> The paper's rough surface on n^2 cells (eps, alpha: its anisotropy, as in paper_rough) under
    !> its one-term solid (Einf/E0 = ratio, 11 when absent) sliding along x at the speed that puts
    !> the loss peak on the wavelength lcell/4
    subroutine sliding_scene(n, h, mat, velocity, error, ratio, eps, alpha)
        integer, intent(in) :: n
        real(dp), intent(out) :: h(n, n), velocity(2)
        type(material_t), intent(out) :: mat
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: ratio, eps, alpha
        real(dp) :: r
        r = 11.0_dp; if (present(ratio)) r = ratio
        call paper_rough(n, h, error, eps, alpha); if (allocated(error)) return
        call paper_solid(r, mat, error); if (allocated(error)) return
        velocity = [peak_speed(r, 4.0_dp), 0.0_dp]
    end subroutine sliding_scene

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

    !> A field mirrored x -> -x about the origin cell
    pure function mirrored(a) result(b)
        real(dp), intent(in) :: a(:, :)
        real(dp) :: b(size(a, 1), size(a, 2))
        integer :: i, n
        n = size(a, 1)
        do i = 1, n
            b(i, :) = a(modulo(1 - i, n) + 1, :)
        end do
    end function mirrored

    !> A square field rotated by +90 degrees about the origin cell
    pure function rotated(a) result(b)
        real(dp), intent(in) :: a(:, :)
        real(dp) :: b(size(a, 1), size(a, 2))
        integer :: i, j, n
        n = size(a, 1)
        do j = 1, n
            do i = 1, n
                b(i, j) = a(j, modulo(1 - i, n) + 1)
            end do
        end do
    end function rotated

    !> max |p - p_ref| / max p_ref
    pure real(dp) function relative_difference(p, p_ref) result(d)
        real(dp), intent(in) :: p(:, :), p_ref(:, :)
        d = maxval(abs(p - p_ref))/maxval(p_ref)
    end function relative_difference

    !> `method` on the paper's rough surface on n^2 cells, pressed to p_mean on an elastic solid
    !> (E = 10 MPa, nu = 0.5), against the dense solution
    subroutine dense_elastic(n, p_mean, error, method)
        integer, intent(in) :: n
        real(dp), intent(in) :: p_mean
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        type(material_t) :: m
        real(dp) :: h(n, n)
        call paper_rough(n, h, error); if (allocated(error)) return
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        call dense_compare(h, m, [0.0_dp, 0.0_dp], p_mean, error, method=method)
    end subroutine dense_elastic

    !> `method` on the sliding scene on 32^2 cells (ratio, eps, alpha as in sliding_scene), pressed
    !> to 100 kPa, against the dense solution; with `base` the solid is a layer on that base, so
    !> thin (q0 d = 0.5) that the longest waves feel it
    subroutine dense_sliding(error, method, ratio, eps, alpha, base)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        real(dp), intent(in), optional :: ratio, eps, alpha
        integer, intent(in), optional :: base
        integer, parameter :: n = 32
        type(material_t) :: m
        real(dp) :: h(n, n), v(2)
        call sliding_scene(n, h, m, v, error, ratio, eps, alpha); if (allocated(error)) return
        if (present(base)) then
            m%thickness_m = 0.5_dp*lcell/(2.0_dp*pi); m%base = base
        end if
        call dense_compare(h, m, v, 1.0e5_dp, error, method=method)
    end subroutine dense_sliding

    !> Heights h on the lcell^2 cell against `mat` moving at `velocity`, pressed to p_mean and solved
    !> by `method`: the contact must be full; the tangential force f, the state, its kernel and the
    !> transforms come back
    subroutine solve_full_contact(h, mat, velocity, p_mean, f, state, kernel, fft, error, method)
        real(dp), intent(in) :: h(:, :), velocity(2), p_mean
        type(material_t), intent(in) :: mat
        real(dp), intent(out) :: f(2)
        type(contact_state_t), intent(out) :: state
        type(kernel_t), intent(out) :: kernel
        type(fft2d_t), intent(out) :: fft
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        call solve_case(h, lcell, lcell, p_mean, state, error, mat=mat, velocity=velocity, kernel=kernel, &
                        method=method)
        if (allocated(error)) return
        call check(error, contact_area_fraction(state%p), 1.0_dp, "not in full contact", abs=0.0_dp)
        if (allocated(error)) return
        call fft%init(size(h, 1), size(h, 2), error, planner='estimate'); if (allocated(error)) return
        f = kernel%tangential_force(fft, state%p)
    end subroutine solve_full_contact

    !> In full contact P(q) = H(q)/K(q) for q /= 0, so the forces are known in closed form: the
    !> sliding scene on 32^2 cells pressed to 20 MPa and solved by `method` has Fx to 1e-10
    !> relative, Fy to 1e-10 of |Fx|; `state` returns the solve
    subroutine check_full_contact_forces(error, method, state)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        type(contact_state_t), intent(out), optional :: state
        integer, parameter :: n = 32
        type(material_t) :: m
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(contact_state_t) :: s
        real(dp) :: h(n, n), v(2), f(2), fe(2)
        call sliding_scene(n, h, m, v, error); if (allocated(error)) return
        call solve_full_contact(h, m, v, 2.0e7_dp, f, s, k, fft, error, method); if (allocated(error)) return
        if (present(state)) state = s
        fe = full_contact_force(k, fft, h)
        call report("rel. error Fx", abs(f(1) - fe(1))/abs(fe(1)))
        call report("rel. error Fy", abs(f(2) - fe(2))/abs(fe(1)))
        call check(error, f(1), fe(1), "Fx", rel=1.0e-10_dp); if (allocated(error)) return
        call check(error, f(2), fe(2), "Fy", abs=1.0e-10_dp*abs(fe(1)))
    end subroutine check_full_contact_forces

    !> A wave (wavevector (3, 2) 2 pi/l, l = 1 m, amplitude wave_h0) on an elastic solid
    !> (E* = 1 MPa) pressed into full contact and solved by `method`: p = p_mean + (E*|q|/2) h
    !> exactly (to 1e-10 of that amplitude); `state` returns the solve
    subroutine check_full_contact_wave(state, error, method)
        type(contact_state_t), intent(out) :: state
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        integer, parameter :: n = 64
        real(dp), parameter :: l = 1.0_dp, h0 = wave_h0, estar = 1.0e6_dp
        real(dp) :: h(n, n), lam, th, amp, p_mean
        lam = l/sqrt(13.0_dp); th = atan2(2.0_dp, 3.0_dp)
        call cosine_surface(square_grid(h, l, l), h0, lam, th, h)
        amp = 0.5_dp*estar*two_pi/lam*h0
        p_mean = 1.5_dp*amp
        call solve_case(h, l, l, p_mean, state, error, estar=estar, method=method); if (allocated(error)) return
        call report("max |p - exact|/p*", maxval(abs(state%p - (p_mean + amp*h/h0)))/amp)
        call check(error, maxval(abs(state%p - (p_mean + amp*h/h0)))/amp <= 1.0e-10_dp, &
                   "pressure differs from p_mean + p* cos(q.x)")
    end subroutine check_full_contact_wave

    !> Errors against Westergaard's solution (h = h0 cos(2 pi x/l), plane strain) on n cells, solved
    !> by `method`: contact width (fraction of l), peak pressure and mean gap (relative)
    subroutine westergaard_errors(n, e_area, e_peak, e_gap, error, method)
        integer, intent(in) :: n
        real(dp), intent(out) :: e_area, e_peak, e_gap
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        real(dp), parameter :: l = 1.0_dp, h0 = 1.0e-3_dp, estar = 1.0e6_dp, p = 1000.0_dp
        real(dp) :: h(n, 1)
        type(contact_state_t) :: s
        type(westergaard_t) :: w
        call cosine_surface(square_grid(h, l, l), h0, l, 0.0_dp, h)
        call solve_case(h, l, l, p, s, error, estar=estar, method=method); if (allocated(error)) return
        w = westergaard(p, h0, l, estar)
        e_area = abs(contact_area_fraction(s%p) - w%width_fraction)
        e_peak = rel_error(maxval(s%p), w%peak_pa)
        e_gap = rel_error(mean_separation(s%g), w%mean_gap_m)
    end subroutine westergaard_errors

    !> Westergaard on 1024 cells, solved by `method`: the width to two cells, the peak pressure to
    !> 5e-6 and the mean gap to 2e-5
    subroutine check_westergaard(error, method)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        integer, parameter :: n = 1024
        real(dp) :: ea, ep, eg
        call westergaard_errors(n, ea, ep, eg, error, method); if (allocated(error)) return
        call report("width error [cells]", ea*n); call report("peak", ep); call report("gap", eg)
        ! the contact edge is resolved to one cell at each end: |error| <= 2/n
        call check(error, ea <= 2.0_dp/n, "contact width off by more than two cells"); if (allocated(error)) return
        ! measured at n = 1024: peak 8.0e-7, mean gap 3.1e-6 (second order in the cell size, see
        ! westergaard-refinement); the bounds leave a factor ~6 for other compilers/FFT plans
        call check(error, ep <= 5.0e-6_dp, "peak pressure"); if (allocated(error)) return
        call check(error, eg <= 2.0e-5_dp, "mean gap")
    end subroutine check_westergaard

    !> Heights h on an (l, l) cell pressed to p_mean (against `mat` moving at `velocity`; as in
    !> solve_case where absent), solved by `method` into s and by `other` into so: the pressures
    !> agree to 1e-9 of max p
    subroutine compare_methods(h, l, p_mean, method, other, s, so, error, mat, velocity)
        real(dp), intent(in) :: h(:, :), l, p_mean
        character(len=*), intent(in) :: method, other
        type(contact_state_t), intent(out) :: s, so
        type(error_t), allocatable, intent(out) :: error
        type(material_t), intent(in), optional :: mat
        real(dp), intent(in), optional :: velocity(2)
        call solve_case(h, l, l, p_mean, s, error, mat=mat, velocity=velocity, method=method)
        if (allocated(error)) return
        call solve_case(h, l, l, p_mean, so, error, mat=mat, velocity=velocity, method=other)
        if (allocated(error)) return
        call report(method//" FFT pairs", real(s%operator_applications, dp))
        call report(other//" FFT pairs", real(so%operator_applications, dp))
        call report("max |dp|/max p", relative_difference(so%p, s%p))
        call check(error, relative_difference(so%p, s%p) <= 1.0e-9_dp, "pressures differ")
    end subroutine compare_methods

    !> Starting from a converged solution costs (almost) nothing: heights h on an (l, l) cell on the
    !> default elastic solid, pressed to p_mean, take `method` more than 10 iterations cold and at
    !> most 2 from the converged pressure
    subroutine check_warm_start(h, l, p_mean, error, method)
        real(dp), intent(in) :: h(:, :), l, p_mean
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        type(contact_state_t) :: s, sw
        call solve_case(h, l, l, p_mean, s, error, method=method); if (allocated(error)) return
        call solve_case(h, l, l, p_mean, sw, error, method=method, p_init=s%p); if (allocated(error)) return
        call report("cold", real(s%iterations, dp)); call report("warm", real(sw%iterations, dp))
        call check(error, sw%iterations <= 2 .and. s%iterations > 10, "warm start did not help")
    end subroutine check_warm_start

    !> fixed_spectrum_surface (q0 .. 16 q0) on 64^2 .. 256^2, pressed to p_mean (against `mat`
    !> moving at `velocity`; as in solve_case where absent), tolerance 1e-8: the FFT pairs of
    !> `method` grow by at most 1.5 from the coarsest grid to the finest
    subroutine check_flat_iterations(p_mean, method, error, mat, velocity)
        real(dp), intent(in) :: p_mean
        character(len=*), intent(in) :: method
        type(error_t), allocatable, intent(out) :: error
        type(material_t), intent(in), optional :: mat
        real(dp), intent(in), optional :: velocity(2)
        real(dp), allocatable :: h(:, :)
        type(contact_state_t) :: s
        integer :: k, n, pairs(3)
        do k = 1, 3
            n = 32*2**k
            call fixed_spectrum_surface(n, 16.0_dp, h, error); if (allocated(error)) return
            call solve_case(h, lcell, lcell, p_mean, s, error, mat=mat, velocity=velocity, tol=1.0e-8_dp, &
                            method=method)
            if (allocated(error)) return
            pairs(k) = s%operator_applications
        end do
        call report("FFT pairs 64^2", real(pairs(1), dp)); call report("128^2", real(pairs(2), dp))
        call report("256^2", real(pairs(3), dp))
        call check(error, pairs(3) <= 1.5_dp*pairs(1), "FFT pairs grow with the grid")
    end subroutine check_flat_iterations

end module solver_fixture
