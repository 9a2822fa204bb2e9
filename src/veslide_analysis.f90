!> Quantities derived from a contact solution: area, separation, forces, dissipation
module veslide_analysis
    use veslide_kinds, only: dp, two_pi
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t, wavevector
    implicit none
    private
    public :: contact_area_fraction, mean_separation, tangential_force, slope_force

contains

    !> Fraction of cells carrying pressure
    pure real(dp) function contact_area_fraction(p) result(a)
        real(dp), intent(in) :: p(:, :)
        a = real(count(p > 0.0_dp), dp)/real(size(p), dp)
    end function contact_area_fraction

    !> Mean gap over the whole cell (zero in contact) [m]
    pure real(dp) function mean_separation(g) result(s)
        real(dp), intent(in) :: g(:, :)
        s = sum(g)/real(size(g), dp)
    end function mean_separation

    !> Tangential force per unit nominal area exerted by the solid on the rigid surface,
    !> F = <p grad w> [Pa], evaluated exactly for the discrete operator:
    !> F = -(1/N^2) sum_q q Im K_d(q) |P(q)|^2 (full-plane sum, Nyquist lines carry no derivative).
    !> Zero for a symmetric (elastic) kernel.
    subroutine tangential_force(kernel, fft, p, f)
        type(kernel_t), intent(in) :: kernel
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: p(:, :)
        real(dp), intent(out) :: f(2)
        integer :: i, j, nx, ny
        real(dp) :: q(2), w
        nx = kernel%nx; ny = kernel%ny
        f = 0.0_dp
        if (kernel%symmetric) return
        fft%x = p
        call fft%forward()
        do j = 1, ny
            do i = 1, nx/2 + 1
                q = wavevector(i, j, nx, ny, kernel%lx_m, kernel%ly_m)
                if (mod(nx, 2) == 0 .and. i == nx/2 + 1 .and. nx > 1) q(1) = 0.0_dp
                if (mod(ny, 2) == 0 .and. j == ny/2 + 1 .and. ny > 1) q(2) = 0.0_dp
                w = merge(1.0_dp, 2.0_dp, i == 1 .or. (mod(nx, 2) == 0 .and. i == nx/2 + 1))
                f = f - w*q*aimag(kernel%kd(i, j))*abs(fft%k(i, j))**2
            end do
        end do
        f = f/(real(nx, dp)*real(ny, dp))**2
    end subroutine tangential_force

    !> The estimator <p grad h> [Pa] (in contact grad w = grad h); spectral derivative of h.
    !> Converges to `tangential_force` under refinement; reported as a check.
    subroutine slope_force(fft, lx, ly, p, h, f)
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: lx, ly, p(:, :), h(:, :)
        real(dp), intent(out) :: f(2)
        complex(dp), allocatable :: hk(:, :)
        real(dp), allocatable :: dh(:, :)
        integer :: i, j, nx, ny, d
        real(dp) :: q(2)
        nx = size(h, 1); ny = size(h, 2)
        fft%x = h
        call fft%forward()
        hk = fft%k
        allocate (dh(nx, ny))
        do d = 1, 2
            do j = 1, ny
                do i = 1, nx/2 + 1
                    q = wavevector(i, j, nx, ny, lx, ly)
                    if (mod(nx, 2) == 0 .and. i == nx/2 + 1 .and. nx > 1) q(1) = 0.0_dp
                    if (mod(ny, 2) == 0 .and. j == ny/2 + 1 .and. ny > 1) q(2) = 0.0_dp
                    fft%k(i, j) = cmplx(0.0_dp, q(d), dp)*hk(i, j)
                end do
            end do
            call fft%backward()
            dh = fft%x
            f(d) = sum(p*dh)/real(nx*ny, dp)
        end do
    end subroutine slope_force

end module veslide_analysis
