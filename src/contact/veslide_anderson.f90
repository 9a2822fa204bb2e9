!> Anderson acceleration (type II) of a fixed-point iteration z <- z + f(z).
!>
!> With memory m the accelerator keeps the last m differences dF_k = f_k - f_{k-1} and
!> G_k = (z_k - z_{k-1}) + dF_k, and replaces the plain step by
!>   z <- z + f - G c,   c = argmin |f - dF c|,
!> solving the m x m least-squares problem from its Gram matrix dF^T dF (LAPACK dposv, with a
!> relative diagonal shift of 1e-10). A step costs one pass over the 2m columns and the grid;
!> the Gram matrix is updated by one new row per step. The previous point is kept as the step
!> that left it (z_k - z_{k-1}, single precision like the history) and its residual (double):
!> memory 2 m + 1 singles and one double per unknown.
!> The unknowns are the rows of a grid's field (nx, ny_local), flattened: dot products are summed
!> row by row and then over the rows in order (veslide_collective), so the step is the same for
!> any number of threads or processes; every process solves the same small system.
!> Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715; Fang & Saad, Numer. Linear Algebra Appl.
!> 16 (2009) 197 (type II).
module veslide_anderson
    use, intrinsic :: iso_fortran_env, only: real32
    use veslide_kinds, only: dp
    use veslide_lapack, only: dposv
    use veslide_grid, only: grid_t
    use veslide_collective, only: ordered_sum
    implicit none
    private
    public :: anderson_t, anderson_coefficients

    type :: anderson_t
        integer :: memory = 0            !! m; 0 gives the plain step
        integer :: stored = 0            !! columns held (<= memory)
        integer :: slot = 0              !! column written last
        logical :: have_prev = .false.   !! a previous step and f are held
        !> the history's columns in single precision (half the memory and traffic; the mixing is
        !> then exact to about 1e-7 of the step, which the fixed-point iteration absorbs: the
        !> residual f itself stays double)
        real(real32), allocatable :: df(:, :), gm(:, :)
        !> the last step z - z_prev, in single precision as the history it feeds (z_prev itself is
        !> z minus the step: no copy of the iterate is kept), and the residual f_prev at z_prev
        real(real32), allocatable :: sprev(:)
        real(dp), allocatable :: gram(:, :), fprev(:)
        real(dp), allocatable :: rows(:, :)  !! per-row partial dot products (2 m, rows)
        type(grid_t) :: grid             !! the grid whose rows the unknowns are (serial: one row)
        integer :: row = 1               !! unknowns per row
    contains
        procedure :: init => anderson_init
        procedure :: reset => anderson_reset
        procedure :: step => anderson_step
        procedure :: plain_step_from_previous => anderson_plain_previous
    end type anderson_t

contains

    !> Set up for n unknowns and memory m (m = 0: no acceleration); with `grid`, the unknowns are
    !> its rows (n = nx ny_local), otherwise one row of n
    subroutine anderson_init(self, n, memory, grid)
        class(anderson_t), intent(inout) :: self
        integer, intent(in) :: n, memory
        type(grid_t), intent(in), optional :: grid
        self%memory = max(0, memory)
        if (present(grid)) then
            self%grid = grid; self%row = grid%nx
        else
            self%grid = grid_t(); self%grid%nx = max(1, n); self%grid%ny = 1; self%row = max(1, n)
        end if
        if (allocated(self%df)) deallocate (self%df, self%gm, self%gram, self%sprev, self%fprev, self%rows)
        allocate (self%df(n, max(self%memory, 1)), self%gm(n, max(self%memory, 1)))
        allocate (self%gram(max(self%memory, 1), max(self%memory, 1)), self%sprev(n), self%fprev(n))
        allocate (self%rows(2*max(self%memory, 1), n/self%row))
        call self%reset()
    end subroutine anderson_init

    !> Forget the history (after a change of the map, or a rejected step)
    pure subroutine anderson_reset(self)
        class(anderson_t), intent(inout) :: self
        self%stored = 0; self%slot = 0; self%have_prev = .false.   ! columns refill from slot 1
    end subroutine anderson_reset

    !> One step from (z, f = residual at z): z <- z + f - G c. Returns .true. when the step was
    !> accelerated (a history existed and the least-squares problem was solved)
    function anderson_step(self, z, f) result(accelerated)
        class(anderson_t), intent(inout) :: self
        real(dp), intent(inout) :: z(:)
        real(dp), intent(in) :: f(:)
        logical :: accelerated
        real(dp) :: coef(max(self%memory, 1))
        real(dp) :: dots(max(self%memory, 1), 2), dfv, zn, part(2*max(self%memory, 1))
        integer :: i, k, n, mk, slot, info, j, nrow, rl
        n = size(z)
        accelerated = .false.
        if (self%memory > 0 .and. self%have_prev) then
            self%slot = modulo(self%slot, self%memory) + 1
            self%stored = min(self%stored + 1, self%memory)
            slot = self%slot; mk = self%stored
            rl = self%row; nrow = n/rl
            ! new columns with the Gram row and the right-hand side, in one pass, row by row
            !$omp parallel do schedule(guided) private(i, dfv, k, part)
            do j = 1, nrow
                part(1:2*mk) = 0.0_dp
                do i = (j - 1)*rl + 1, j*rl
                    dfv = f(i) - self%fprev(i)
                    self%df(i, slot) = real(dfv, real32)
                    self%gm(i, slot) = real(real(self%sprev(i), dp) + dfv, real32)
                    dfv = real(self%df(i, slot), dp)
                    do k = 1, mk
                        part(k) = part(k) + real(self%df(i, k), dp)*dfv
                        part(mk + k) = part(mk + k) + real(self%df(i, k), dp)*f(i)
                    end do
                end do
                self%rows(1:2*mk, j) = part(1:2*mk)
            end do
            !$omp end parallel do
            call ordered_sum(self%grid, self%rows(1:2*mk, :), part(1:2*mk))
            dots(1:mk, 1) = part(1:mk); dots(1:mk, 2) = part(mk + 1:2*mk)
            self%gram(1:mk, slot) = dots(1:mk, 1); self%gram(slot, 1:mk) = dots(1:mk, 1)
            call anderson_coefficients(self%gram, mk, dots(1:mk, 2), coef, info)
            if (info /= 0) then
                self%stored = 0; mk = 0; coef = 0.0_dp
            end if
            accelerated = info == 0
            ! the update of z, keeping the step and f for the next
            !$omp parallel do schedule(guided) private(zn, k)
            do i = 1, n
                zn = z(i) + f(i)
                do k = 1, mk
                    zn = zn - real(self%gm(i, k), dp)*coef(k)
                end do
                self%sprev(i) = real(zn - z(i), real32); self%fprev(i) = f(i)
                z(i) = zn
            end do
            !$omp end parallel do
        else
            self%sprev = real(f, real32); self%fprev = f
            z = z + f
        end if
        self%have_prev = .true.
    end function anderson_step

    !> The mixing coefficients c = argmin |f - dF c| from the Gram matrix dF^T dF (leading mk x mk
    !> block of `gram`) and rhs = dF^T f: regularised normal equations (relative diagonal shift
    !> 1e-10), LAPACK dposv. info /= 0: not positive definite (c undefined)
    subroutine anderson_coefficients(gram, mk, rhs, coef, info)
        real(dp), intent(in) :: gram(:, :), rhs(:)
        integer, intent(in) :: mk
        real(dp), intent(out) :: coef(:)
        integer, intent(out) :: info
        real(dp) :: gtmp(mk, mk)
        integer :: k
        gtmp = gram(1:mk, 1:mk)
        do k = 1, mk
            gtmp(k, k) = gtmp(k, k)*(1.0_dp + 1.0e-10_dp)
        end do
        coef(1:mk) = rhs(1:mk)
        call dposv('U', mk, 1, gtmp, mk, coef, size(coef), info)
    end subroutine anderson_coefficients

    !> z <- z_prev + f_prev (the plain step from the previous point, replacing a rejected
    !> accelerated step; z_prev = z - the stored step, exact to single precision of the step),
    !> and the history cleared
    subroutine anderson_plain_previous(self, z)
        class(anderson_t), intent(inout) :: self
        !> on entry the point the rejected step reached
        real(dp), intent(inout) :: z(:)
        z = (z - real(self%sprev, dp)) + self%fprev
        call self%reset()
    end subroutine anderson_plain_previous

end module veslide_anderson
