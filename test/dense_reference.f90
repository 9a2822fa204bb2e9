!> Exact reference for small grids: the full influence matrix and a finite-termination
!> complementarity solver with a KKT certificate.
!>
!> Problem: p >= 0, g = A p - h + d >= 0, p g = 0, sum(p) = n p_mean, d free; A dense (not
!> necessarily symmetric) with A + A^T positive definite on zero-mean vectors, so the solution
!> is unique. Block principal pivoting (Judice & Pires 1994): given the contact set I, solve
!> [A_II 1; 1^T 0] [p_I; d] = [h_I; n p_mean] with LAPACK, flip every infeasible index; when
!> the number of infeasibilities stops falling, flip only the largest-index one (Murty's rule,
!> which terminates for P-matrices). The result is accepted only with its KKT residuals.
module dense_reference
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t
    use veslide_lapack, only: dgesv
    implicit none
    private
    public :: influence_matrix, solve_dense

contains

    !> Column j of A is K applied to a unit pressure in cell j (column-major cell order)
    subroutine influence_matrix(kernel, a, error)
        type(kernel_t), intent(in) :: kernel
        real(dp), allocatable, intent(out) :: a(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: fft
        real(dp), allocatable :: e(:, :), col(:, :)
        integer :: j, n, nx, ny
        nx = kernel%grid%nx; ny = kernel%grid%ny; n = nx*ny
        call fft%init(nx, ny, error, planner='estimate'); if (allocated(error)) return
        allocate (a(n, n), e(nx, ny), col(nx, ny))
        do j = 1, n
            e = 0.0_dp
            e(mod(j - 1, nx) + 1, (j - 1)/nx + 1) = 1.0_dp
            call kernel%apply(fft, e, col)
            a(:, j) = reshape(col, [n])
        end do
    end subroutine influence_matrix

    !> Solve the dense problem; `kkt` returns max(penetration, |p g|, -p) relative to h_s, p_mean
    subroutine solve_dense(a, h, p_mean, p, d, kkt, error)
        real(dp), intent(in) :: a(:, :), h(:), p_mean
        real(dp), intent(out) :: p(:), d, kkt
        type(error_t), allocatable, intent(out) :: error
        logical, allocatable :: in_set(:)
        real(dp), allocatable :: m(:, :), rhs(:), g(:)
        integer, allocatable :: ipiv(:), idx(:)
        integer :: n, k, nin, info, it, ninf, best, tries, last
        real(dp) :: hs, tolp, tolg
        n = size(h)
        hs = sqrt(sum((h - sum(h)/n)**2)/n)
        allocate (in_set(n), g(n))
        in_set = h >= sum(h)/n          ! start from the upper half of the surface
        best = n + 1; tries = 0
        do it = 1, 50*n
            nin = count(in_set)
            idx = pack([(k, k = 1, n)], in_set)
            allocate (m(nin + 1, nin + 1), rhs(nin + 1), ipiv(nin + 1))
            m(1:nin, 1:nin) = a(idx, idx)
            m(1:nin, nin + 1) = 1.0_dp
            m(nin + 1, 1:nin) = 1.0_dp
            m(nin + 1, nin + 1) = 0.0_dp
            rhs(1:nin) = h(idx); rhs(nin + 1) = n*p_mean
            call dgesv(nin + 1, 1, m, nin + 1, ipiv, rhs, nin + 1, info)
            if (info /= 0) then
                call fatal_error(error, "dense_reference: singular contact system"); return
            end if
            p = 0.0_dp; p(idx) = rhs(1:nin); d = rhs(nin + 1)
            g = matmul(a, p) - h + d
            deallocate (m, rhs, ipiv)
            tolp = 1.0e-13_dp*p_mean*n; tolg = 1.0e-13_dp*hs
            ninf = count(in_set .and. p < -tolp*1.0e-3_dp) + count(.not. in_set .and. g < -tolg)
            if (ninf == 0) exit
            if (ninf < best) then
                best = ninf; tries = 0
            else
                tries = tries + 1
            end if
            if (tries <= 3) then
                where (in_set .and. p < -tolp*1.0e-3_dp)
                    in_set = .false.
                elsewhere (.not. in_set .and. g < -tolg)
                    in_set = .true.
                end where
            else
                do last = n, 1, -1
                    if ((in_set(last) .and. p(last) < -tolp*1.0e-3_dp) .or. (.not. in_set(last) .and. g(last) < -tolg)) exit
                end do
                in_set(last) = .not. in_set(last)
            end if
        end do
        if (ninf /= 0) then
            call fatal_error(error, "dense_reference: no complementary basis found"); return
        end if
        kkt = max(maxval(max(-g, 0.0_dp))/hs, abs(sum(p*g))/(sum(p)*hs), maxval(max(-p, 0.0_dp))/p_mean)
    end subroutine solve_dense

end module dense_reference
