!> Second spectral moments of fields on the grid: the slope tensor M_ij = <d_i h d_j h>,
!> optionally restricted to a band of |q| (Parseval on the half-spectrum, with the grid's
!> Hermitian weights; Nyquist lines carry no derivative).
module veslide_spectrum
    use veslide_kinds, only: dp
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    use veslide_collective, only: ordered_sum
    implicit none
    private
    public :: spectrum_slope_tensor, slope_tensor

contains

    !> Slope tensor of the field whose half-spectrum is `ak` (the grid's spectral storage), times
    !> scale^2: M = scale^2 sum_q w q q |ak|^2 over band(1) <= |q| <= band(2) [1/m] (all q when
    !> absent). For coefficients of h = sum_q a_q exp(i q.x) scale = 1; for FFTW's output 1/(nx ny).
    subroutine spectrum_slope_tensor(grid, ak, m, band, scale)
        type(grid_t), intent(in) :: grid
        complex(dp), intent(in) :: ak(:, :)
        real(dp), intent(out) :: m(2, 2)
        real(dp), intent(in), optional :: band(2), scale
        integer :: a, b, i, j, ij(2)
        real(dp) :: q(2), dq(2), p2, qn, cols(3, size(ak, 2)), t(3)
        ! the wavevector and derivative wavevector of every half-spectrum row i and column j, and
        ! the Hermitian weight of every row, made once (the same values grid%wavevector,
        ! derivative_wavevector and hermitian_weight give entry by entry)
        real(dp) :: qx(grid%nq()), qy(grid%ny), dqx(grid%nq()), dqy(grid%ny), w(grid%nq())
        do i = 1, grid%nq()
            q = grid%wavevector(i, 1); qx(i) = q(1)
            q = grid%derivative_wavevector(i, 1); dqx(i) = q(1)
            w(i) = grid%hermitian_weight(i)
        end do
        do j = 1, grid%ny
            q = grid%wavevector(1, j); qy(j) = q(2)
            q = grid%derivative_wavevector(1, j); dqy(j) = q(2)
        end do
        !$omp parallel do schedule(guided) private(a, i, j, ij, dq, p2, qn)
        do b = 1, size(ak, 2)
            cols(:, b) = 0.0_dp
            do a = 1, size(ak, 1)
                ij = grid%spectral_index(a, b); i = ij(1); j = ij(2)
                if (present(band)) then
                    qn = norm2([qx(i), qy(j)])
                    if (qn < band(1) .or. qn > band(2)) cycle
                end if
                dq = [dqx(i), dqy(j)]
                p2 = w(i)*abs(ak(a, b))**2
                cols(:, b) = cols(:, b) + [dq(1)*dq(1), dq(2)*dq(2), dq(1)*dq(2)]*p2
            end do
        end do
        !$omp end parallel do
        call ordered_sum(grid, cols, t, spectral=.true.)
        m(1, 1) = t(1); m(2, 2) = t(2); m(1, 2) = t(3)
        if (present(scale)) m = m*scale**2
        m(2, 1) = m(1, 2)
    end subroutine spectrum_slope_tensor

    !> Slope tensor M_ij = <d_i h d_j h> of a real field h, optionally in the band
    !> band(1) <= |q| <= band(2) [1/m]; uses the buffers of `fft`
    subroutine slope_tensor(grid, fft, h, m, band)
        type(grid_t), intent(in) :: grid
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: h(:, :)
        real(dp), intent(out) :: m(2, 2)
        real(dp), intent(in), optional :: band(2)
        fft%x = h
        call fft%forward()
        call spectrum_slope_tensor(grid, fft%k, m, band, scale=1.0_dp/grid%cells())
    end subroutine slope_tensor

end module veslide_spectrum
