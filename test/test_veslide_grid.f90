!> The grid's spectral rules, the FFT wrapper, and spectral moments against closed forms
module test_veslide_grid
    use veslide_kinds, only: dp, i8, pi, two_pi
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_spectrum, only: slope_tensor
    use veslide_surface, only: psd_t, random_surface, cosine_surface
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
    implicit none
    private
    public :: collect_grid, collect_fftw

contains

    subroutine collect_grid(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("wavevectors-and-nyquist-lines", test_wavevectors), &
            new_unittest("hermitian-weights-count-every-mode", test_weights), &
            new_unittest("slope-tensor-of-a-wave", test_wave_slope), &
            new_unittest("non-positive-size-refused", test_bad_grid, should_fail=.true., &
                         expect="lx_m and ly_m must be positive") &
            ]
    end subroutine collect_grid

    subroutine collect_fftw(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("round-trip", test_round_trip), &
            new_unittest("blocks-equal-the-dft", test_against_dft), &
            new_unittest("same-bits-on-any-number-of-threads", test_thread_bits), &
            new_unittest("isolated-plan-ignores-wisdom", test_isolated) &
            ]
    end subroutine collect_fftw

    subroutine test_wavevectors(error)
        type(error_t), allocatable, intent(out) :: error
        type(grid_t) :: g
        real(dp) :: q(2)
        call new_grid(g, 8, 6, 2.0_dp, 3.0_dp, error); if (allocated(error)) return
        call check(error, g%nq() == 5 .and. all(g%wavenumber(2, 6) == [1, -1]) .and. all(g%wavenumber(5, 4) == [4, 3]), &
                   "wavenumbers")
        if (allocated(error)) return
        q = g%wavevector(3, 5)
        call check(error, abs(q(1) - two_pi*2/2.0_dp) < 1.0e-15_dp .and. abs(q(2) + two_pi*2/3.0_dp) < 1.0e-15_dp, &
                   "wavevector")
        if (allocated(error)) return
        call check(error, g%is_nyquist_x(5) .and. .not. g%is_nyquist_x(4) .and. g%is_nyquist_y(4), "Nyquist lines")
        if (allocated(error)) return
        q = g%derivative_wavevector(5, 4)
        call check(error, all(q == 0.0_dp), "no derivative on the Nyquist lines")
    end subroutine test_wavevectors

    !> The weights of the half-spectrum sum to the number of full-plane modes, nx*ny, on even and
    !> odd grids
    subroutine test_weights(error)
        type(error_t), allocatable, intent(out) :: error
        type(grid_t) :: g
        integer :: sizes(2, 4), k, i
        real(dp) :: w
        sizes = reshape([8, 6, 7, 5, 8, 1, 1, 9], [2, 4])
        do k = 1, 4
            call new_grid(g, sizes(1, k), sizes(2, k), 1.0_dp, 1.0_dp, error); if (allocated(error)) return
            w = sum([(g%hermitian_weight(i), i = 1, g%nq())])*g%ny
            call check(error, w, g%cells(), "weights of an nx x ny grid", rel=0.0_dp); if (allocated(error)) return
        end do
    end subroutine test_weights

    !> h = A cos(q.x): the slope tensor is A^2/2 q q^T exactly
    subroutine test_wave_slope(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 32
        type(grid_t) :: g
        type(fft2d_t) :: fft
        real(dp) :: h(n, n), m(2, 2), q(2), th
        call new_grid(g, n, n, 1.0_dp, 1.0_dp, error); if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        th = atan2(2.0_dp, 3.0_dp)
        call cosine_surface(g, 1.0e-3_dp, 1.0_dp/sqrt(13.0_dp), th, h)
        call slope_tensor(g, fft, h, m)
        q = two_pi*[3.0_dp, 2.0_dp]
        call report("max error", maxval(abs(m - 0.5e-6_dp*reshape([q(1)*q(1), q(1)*q(2), q(1)*q(2), q(2)*q(2)], &
                    [2, 2])))/(0.5e-6_dp*q(1)**2))
        call check(error, maxval(abs(m - 0.5e-6_dp*reshape([q(1)*q(1), q(1)*q(2), q(1)*q(2), q(2)*q(2)], [2, 2]))) &
                   <= 1.0e-13_dp*0.5e-6_dp*q(1)**2, "slope tensor of a wave")
    end subroutine test_wave_slope

    subroutine test_bad_grid(error)
        type(error_t), allocatable, intent(out) :: error
        type(grid_t) :: g
        call new_grid(g, 8, 8, 1.0_dp, -1.0_dp, error)
    end subroutine test_bad_grid

    subroutine test_round_trip(error)
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: fft
        real(dp) :: x(12, 10)
        call fft%init(12, 10, error, planner='estimate'); if (allocated(error)) return
        call random_number(x)
        fft%x = x; call fft%forward(); call fft%backward()
        call report("max |x - IFFT FFT x|", maxval(abs(fft%x - x)))
        call check(error, maxval(abs(fft%x - x)) <= 1.0e-15_dp, "backward(forward(x)) /= x")
    end subroutine test_round_trip

    !> The transform done in blocks of rows and spectral columns (full and shorter last blocks
    !> in both directions, and a single row) equals the DFT sum_x f(x) exp(-i q.x) evaluated directly
    subroutine test_against_dft(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: shapes(2, 3) = reshape([40, 37, 7, 18, 64, 1], [2, 3])
        type(fft2d_t) :: fft
        real(dp), allocatable :: x(:, :)
        complex(dp) :: s
        real(dp) :: worst, e
        integer :: m, nx, ny, a, b, i, j
        worst = 0.0_dp
        do m = 1, size(shapes, 2)
            nx = shapes(1, m); ny = shapes(2, m)
            call fft%init(nx, ny, error, planner='estimate'); if (allocated(error)) return
            allocate (x(nx, ny)); call random_number(x)
            fft%x = x; call fft%forward()
            e = 0.0_dp
            do b = 1, ny
                do a = 1, nx/2 + 1
                    s = (0.0_dp, 0.0_dp)
                    do j = 1, ny
                        do i = 1, nx
                            s = s + x(i, j)*exp(cmplx(0.0_dp, -two_pi*(real((a - 1)*(i - 1), dp)/nx + &
                                                                       real((b - 1)*(j - 1), dp)/ny), dp))
                        end do
                    end do
                    e = max(e, abs(fft%k(a, b) - s))
                end do
            end do
            worst = max(worst, e/sum(abs(x)))
            call fft%backward()
            worst = max(worst, maxval(abs(fft%x - x)))
            deallocate (x)
        end do
        call report("max |FFT - DFT|/sum|x|, |x - IFFT FFT x|", worst)
        call check(error, worst <= 1.0e-14_dp, "the blocked transform differs from the DFT")
    end subroutine test_against_dft

    !> The blocks are fixed by the grid: forward and backward give bitwise the same on 1, 2 and 3
    !> threads (a grid of several blocks each way, the last ones shorter)
    subroutine test_thread_bits(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: nx = 250, ny = 70
        type(fft2d_t) :: fft
        real(dp) :: x(nx, ny), y(nx, ny, 3)
        complex(dp) :: k(nx/2 + 1, ny, 3)
        integer :: t, t0
        call fft%init(nx, ny, error, planner='estimate'); if (allocated(error)) return
        call random_number(x)
        t0 = 1
        !$ t0 = omp_get_max_threads()
        do t = 1, 3
            !$ call omp_set_num_threads(t)
            fft%x = x; call fft%forward(); k(:, :, t) = fft%k
            fft%k = cmplx(real(k(:, :, t))**2, aimag(k(:, :, t)), dp)
            call fft%backward(); y(:, :, t) = fft%x
        end do
        !$ call omp_set_num_threads(t0)
        call check(error, all(k(:, :, 2) == k(:, :, 1)) .and. all(k(:, :, 3) == k(:, :, 1)) .and. &
                   all(y(:, :, 2) == y(:, :, 1)) .and. all(y(:, :, 3) == y(:, :, 1)), &
                   "the transforms differ between 1, 2 and 3 threads")
    end subroutine test_thread_bits

    !> The surface generator's isolated plan gives bitwise the same heights whether or not the
    !> process planned a transform of the same size with FFTW_MEASURE before (whose wisdom an
    !> ordinary FFTW_ESTIMATE plan would reuse)
    subroutine test_isolated(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 96
        type(grid_t) :: g
        type(fft2d_t) :: fft
        type(psd_t) :: psd
        real(dp) :: h1(n, n), h2(n, n)
        call new_grid(g, n, n, 1.0_dp, 1.0_dp, error); if (allocated(error)) return
        psd = psd_t(hurst=0.8_dp, q_low=two_pi, q_roll=two_pi, q_cut=40*two_pi)
        call random_surface(g, psd, 3_i8, 0.025_dp, 0.0_dp, h1, error); if (allocated(error)) return
        call fft%init(n, n, error, planner='patient'); if (allocated(error)) return
        call random_surface(g, psd, 3_i8, 0.025_dp, 0.0_dp, h2, error); if (allocated(error)) return
        call check(error, all(h1 == h2), "heights changed after another plan was made")
    end subroutine test_isolated

end module test_veslide_grid
