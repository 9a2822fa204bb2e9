!> Closed-form and exact references shared by several test suites
module reference_oracles
    use veslide_kinds, only: dp, i8, pi, two_pi
    use veslide_error, only: error_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_surface, only: psd_t, random_surface
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t
    use veslide_material, only: material_t, new_one_term
    implicit none
    private
    public :: westergaard_t, westergaard, full_contact_force, paper_solid, paper_rough, peak_speed, einf, tau, lcell
    public :: dugdale_crack_toughening

    !> The paper's solid and cell: glassy modulus [Pa], retardation time [s], cell side [m]
    real(dp), parameter :: einf = 1.0e8_dp, tau = 1.0e-2_dp, lcell = 1.0e-2_dp

    !> Westergaard's solution of a wave h0 cos(2 pi x/l) pressed on an elastic half-plane
    type :: westergaard_t
        real(dp) :: width_fraction = 0.0_dp   !! contact width / l
        real(dp) :: peak_pa = 0.0_dp          !! maximum pressure
        real(dp) :: mean_gap_m = 0.0_dp       !! mean separation
    end type westergaard_t

contains

    !> The paper's one-term solid with Einf/E0 = ratio (nu = 0.5)
    subroutine paper_solid(ratio, mat, error)
        real(dp), intent(in) :: ratio
        type(material_t), intent(out) :: mat
        type(error_t), allocatable, intent(out) :: error
        call new_one_term(mat, einf, ratio, tau, 0.5_dp, error)
    end subroutine paper_solid

    !> The rough surface of the physics tests: self-affine on an n^2 grid of the lcell^2 cell,
    !> spectrum q0 .. n/4 q0, H = 0.8, realised rms slope 0.025, seed 5 (eps, alpha optional)
    subroutine paper_rough(n, h, error, eps, alpha)
        integer, intent(in) :: n
        real(dp), intent(out) :: h(n, n)
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: eps, alpha
        type(psd_t) :: psd
        type(grid_t) :: grid
        real(dp) :: q0
        q0 = two_pi/lcell
        psd = psd_t(hurst=0.8_dp, q_low=q0, q_roll=q0, q_cut=q0*n/4)
        if (present(eps)) psd%eccentricity = eps
        if (present(alpha)) psd%alpha_rad = alpha
        call new_grid(grid, n, n, lcell, lcell, error); if (allocated(error)) return
        call random_surface(grid, psd, 5_i8, 0.025_dp, 0.0_dp, h, error)
    end subroutine paper_rough

    !> Speed at which the wavelength lcell/k sees the loss peak w = Einf/(E0 tau) of paper_solid
    pure real(dp) function peak_speed(ratio, k) result(v)
        real(dp), intent(in) :: ratio, k
        v = ratio/tau/(two_pi*k/lcell)
    end function peak_speed

    !> Plane strain, psi = sin(pi a/l) = sqrt(p/p*), p* = pi E* h0/l; peak pressure 2 sqrt(p p*);
    !> mean gap h0 + 2 p l/(pi E*) (ln psi - 1/2) (docs/validation.md derives it from g(0) = 0
    !> and sum_k cos(k t)/k = -ln|2 sin(t/2)|)
    pure function westergaard(p, h0, l, estar) result(w)
        real(dp), intent(in) :: p, h0, l, estar
        type(westergaard_t) :: w
        real(dp) :: pstar, psi
        pstar = pi*estar*h0/l
        psi = sqrt(p/pstar)
        w%width_fraction = 2.0_dp*asin(psi)/pi
        w%peak_pa = 2.0_dp*sqrt(p*pstar)
        w%mean_gap_m = h0 + 2.0_dp*p*l/(pi*estar)*(log(psi) - 0.5_dp)
    end function westergaard

    !> The exact tangential force of the solid on the rigid surface h in full contact, for the
    !> discrete operator: p(q) = h(q)/K(q) (q /= 0), so F = -(1/N^4) sum_q w q Im K |H/K|^2 with H the
    !> unnormalised transform of h (Nyquist lines carry no derivative). Any surface, any kernel.
    function full_contact_force(kernel, fft, h) result(f)
        type(kernel_t), intent(in) :: kernel
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: h(:, :)
        real(dp) :: f(2)
        integer :: i, j
        f = 0.0_dp
        fft%x = h; call fft%forward()
        associate (g => kernel%grid)
            do j = 1, g%ny
                do i = 1, g%nq()
                    if (i == 1 .and. j == 1) cycle
                    f = f - g%hermitian_weight(i)*g%derivative_wavevector(i, j)*aimag(kernel%value(i, j)) &
                        *abs(fft%k(i, j)/kernel%value(i, j))**2
                end do
            end do
            f = f/g%cells()**2
        end associate
    end function full_contact_force

    !> A steady crack with a Dugdale zone opening into a one-term viscoelastic solid (creep
    !> compliance J(t) E0 = 1 - (1 - E0/Einf) exp(-t/tau)) at the speed v: the far field's energy
    !> release rate over the work of adhesion, G/w = r, as a function of v tau/a0 (a0 = pi E0* w/
    !> (4 sigma0^2), the zone at rest) and Einf/E0. Derivation (docs/adhesion.md, *Trailing
    !> edges*): the stress is that of the elastic crack of the same K (each material point crosses
    !> from the bonded side into the zone and then the free surface, so the region where tractions
    !> are prescribed only grows along its path: Graham's and Schapery's correspondence); the
    !> zone's length a = (pi/8) (K/sigma0)^2 = a0 r; a material point crossing the zone opens by
    !> the creep integral of the elastic opening's increments, which the zone's end makes w/sigma0:
    !>   1/r = integral over xi in (0, 1) of J((1 - xi) a/v) E0 dD(xi),
    !> D(xi) = b - ((1 - b^2)/2) ln((1 + b)/(1 - b)), b = sqrt(xi), the relaxed elastic opening
    !> of the semi-infinite Dugdale crack over its end value (Schapery's and Greenwood's
    !> steady-crack analyses; here in closed form but for the quadrature). Solved for r by damped
    !> fixed-point iteration; the quadrature on 20000 intervals (exact D differences, the creep
    !> term at their midpoints) is good to about 1e-7.
    pure real(dp) function dugdale_crack_toughening(speed_ratio, einf_over_e0) result(r)
        real(dp), intent(in) :: speed_ratio, einf_over_e0
        integer, parameter :: intervals = 20000
        real(dp) :: xi(0:intervals), d(0:intervals), integral, rn, b
        integer :: k, it
        do k = 0, intervals
            xi(k) = real(k, dp)/intervals
            b = sqrt(xi(k))
            if (k == intervals) then
                d(k) = 1.0_dp
            else
                d(k) = b - 0.5_dp*(1.0_dp - b*b)*log((1.0_dp + b)/(1.0_dp - b))
            end if
        end do
        r = 1.0_dp
        do it = 1, 2000
            integral = 0.0_dp
            do k = 1, intervals
                integral = integral + &
                           exp(-(1.0_dp - 0.5_dp*(xi(k) + xi(k - 1)))*r/speed_ratio)*(d(k) - d(k - 1))
            end do
            rn = 1.0_dp/(1.0_dp - (1.0_dp - 1.0_dp/einf_over_e0)*integral)
            if (abs(rn - r) <= 1.0e-12_dp*r) exit
            r = 0.5_dp*(r + rn)
        end do
        r = rn
    end function dugdale_crack_toughening

end module reference_oracles
