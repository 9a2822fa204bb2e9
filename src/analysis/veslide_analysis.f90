!> Quantities derived from a contact solution: area, separation, the slope-force estimator.
!> (The exact tangential force of the discrete operator is the kernel's `tangential_force`.)
module veslide_analysis
    use veslide_kinds, only: dp
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    implicit none
    private
    public :: contact_area_fraction, mean_separation, slope_force

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

    !> The estimator <p grad h> [Pa] (in contact grad w = grad h); spectral derivative of h.
    !> Converges to the kernel's `tangential_force` under refinement; reported as a check.
    subroutine slope_force(grid, fft, p, h, f)
        type(grid_t), intent(in) :: grid
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: p(:, :), h(:, :)
        real(dp), intent(out) :: f(2)
        complex(dp), allocatable :: hk(:, :)
        integer :: i, j, d
        real(dp) :: q(2)
        fft%x = h
        call fft%forward()
        hk = fft%k
        do d = 1, 2
            do j = 1, grid%ny
                do i = 1, grid%nq()
                    q = grid%derivative_wavevector(i, j)
                    fft%k(i, j) = cmplx(0.0_dp, q(d), dp)*hk(i, j)
                end do
            end do
            call fft%backward()
            f(d) = sum(p*fft%x)/grid%cells()
        end do
    end subroutine slope_force

end module veslide_analysis
