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
    use veslide_material, only: material_t
    use veslide_contact, only: contact_state_t
    use veslide_analysis, only: contact_area_fraction
    use testsuite, only: check, report
    use test_support, only: solve_case
    use reference_oracles, only: lcell
    implicit none
    private
    public :: influence_matrix, solve_dense, dense_compare

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

    !> The FFT solver (`method`, default 'auto') on heights h (cell lcell) against the dense
    !> solution of the same discrete problem: the dense solution must be certified (KKT <= 1e-11)
    !> and the pressures agree to 1e-9 of max p; `area` returns the solver's contact fraction
    subroutine dense_compare(h, mat, v, p_mean, error, method, area, device)
        real(dp), intent(in) :: h(:, :), v(2), p_mean
        type(material_t), intent(in) :: mat
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: method
        real(dp), intent(out), optional :: area
        !> where to solve ('auto' when absent)
        character(len=*), intent(in), optional :: device
        type(contact_state_t) :: s
        type(kernel_t) :: k
        real(dp), allocatable :: a(:, :), p(:)
        real(dp) :: d, kkt, diff
        integer :: n
        n = size(h)
        call solve_case(h, lcell, lcell, p_mean, s, error, mat=mat, velocity=v, tol=1.0e-13_dp, kernel=k, &
                        method=method, device=device)
        if (allocated(error)) return
        if (present(method)) then
            call check(error, s%method == method, "method used: "//s%method); if (allocated(error)) return
        end if
        call influence_matrix(k, a, error); if (allocated(error)) return
        allocate (p(n))
        call solve_dense(a, reshape(h - sum(h)/n, [n]), p_mean, p, d, kkt, error); if (allocated(error)) return
        diff = maxval(abs(reshape(s%p, [n]) - p))/maxval(p)
        call report("dense KKT", kkt); call report("max |dp|/max p", diff)
        call report("area", contact_area_fraction(s%p)); call report("iterations", real(s%iterations, dp))
        if (present(area)) area = contact_area_fraction(s%p)
        call check(error, kkt <= 1.0e-11_dp, "dense solution not certified"); if (allocated(error)) return
        call check(error, diff <= 1.0e-9_dp, "the FFT solver ("//trim(s%method)//" on "//s%device// &
                   ") differs from the dense solution")
    end subroutine dense_compare

end module dense_reference
