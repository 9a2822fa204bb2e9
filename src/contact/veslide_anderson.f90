!> Anderson acceleration (type II) of a fixed-point iteration z <- z + f(z): the one
!> implementation the splittings use (dr with its Douglas-Rachford map fused into the passes,
!> pdr's mixing with its residual given), on the host or the device.
!>
!> With memory m the accelerator keeps the last m differences dF_k = f_k - f_{k-1} and
!> G_k = (z_k - z_{k-1}) + dF_k (single precision: half the memory and traffic of the mixing, which
!> is then exact to about 1e-7 of the step, absorbed by the fixed-point iteration), the previous
!> point z_prev and its residual f_prev (double), and replaces the plain step by
!>   z <- z + f - G c,   c = argmin |f - dF c|,
!> solving the m x m least-squares problem from its Gram matrix dF^T dF (LAPACK dposv, with a
!> relative diagonal shift of 1e-10); the Gram matrix gains one row per step. A step is two
!> passes over the grid (veslide_anderson_passes): `columns` (the new history column and its
!> products, with the residual's norm; for dr the map's y and f computed from x and z on the way)
!> and `update`. Memory per unknown: 8 m (history) + 16 (z_prev, f_prev) bytes.
!> The unknowns are the rows of a grid's field (n1, n2_local): dot products are summed row by row
!> and then over the rows in order (veslide_collective), so the step is the same for any number
!> of threads or processes; every process solves the same small system.
!> Walker & Ni, SIAM J. Numer. Anal. 49 (2011) 1715; Fang & Saad, Numer. Linear Algebra Appl.
!> 16 (2009) 197 (type II).
module veslide_anderson
    use veslide_kinds, only: dp
    use veslide_lapack, only: dposv
    use veslide_grid, only: grid_t
    use veslide_collective, only: ordered_sum
    use veslide_arrays, only: rarray_t, sarray_t
    use veslide_anderson_passes, only: anderson_columns, anderson_update
    use veslide_contact_law, only: contact_law_t
    implicit none
    private
    public :: anderson_t, anderson_coefficients

    type :: anderson_t
        integer :: memory = 0            !! m; 0 gives the plain step
        integer :: stored = 0            !! columns held (<= memory)
        integer :: slot = 0              !! column written last
        logical :: have_prev = .false.   !! a previous point and its f are held
        type(sarray_t) :: df, gm         !! the history's columns (n, max(m, 1))
        type(rarray_t) :: zprev, fprev   !! the previous point and its residual
        real(dp), allocatable :: gram(:, :)
        real(dp), allocatable :: rows(:, :)  !! per-row partial sums (1 + 2 m, rows)
        type(grid_t) :: grid             !! the grid whose rows the unknowns are (or one row)
    contains
        procedure :: init => anderson_init
        procedure :: reset => anderson_reset
        procedure :: destroy => anderson_destroy
        procedure :: begin => anderson_begin
        procedure :: again => anderson_again
        procedure :: columns => anderson_columns_step
        procedure :: mix => anderson_mix
        procedure :: update => anderson_update_step
        generic :: step => step_fields, step_arrays
        procedure, private :: step_fields, step_arrays
        procedure :: plain_step_from_previous => anderson_plain_previous
    end type anderson_t

contains

    !> Set up for a field of n1 x n2 unknowns (the rows of `grid`, which may be distributed; without
    !> it, n1 x n2 unknowns of one process) and memory m (0: no acceleration), on the device or not
    subroutine anderson_init(self, n1, n2, memory, device, grid)
        class(anderson_t), intent(inout) :: self
        integer, intent(in) :: n1, n2, memory
        logical, intent(in) :: device
        type(grid_t), intent(in), optional :: grid
        call self%destroy()
        self%memory = max(0, memory)
        if (present(grid)) then
            self%grid = grid
        else
            self%grid = grid_t(); self%grid%nx = n1; self%grid%ny = n2
        end if
        call self%df%create(n1*n2, max(self%memory, 1), device)
        call self%gm%create(n1*n2, max(self%memory, 1), device)
        call self%zprev%create(n1, n2, device)
        call self%fprev%create(n1, n2, device)
        allocate (self%gram(max(self%memory, 1), max(self%memory, 1)), self%rows(1 + 2*max(self%memory, 1), n2))
        call self%reset()
    end subroutine anderson_init

    !> Forget the history (after a change of the map, or a rejected step)
    pure subroutine anderson_reset(self)
        class(anderson_t), intent(inout) :: self
        self%stored = 0; self%slot = 0; self%have_prev = .false.   ! columns refill from slot 1
    end subroutine anderson_reset

    subroutine anderson_destroy(self)
        class(anderson_t), intent(inout) :: self
        call self%df%destroy(); call self%gm%destroy(); call self%zprev%destroy(); call self%fprev%destroy()
        if (allocated(self%gram)) deallocate (self%gram, self%rows)
    end subroutine anderson_destroy

    !> A new point: the columns its step will use (mk), the slot advanced to the one it writes
    !> (0 columns without a previous point or memory)
    integer function anderson_begin(self) result(mk)
        class(anderson_t), intent(inout) :: self
        mk = 0
        if (self%memory > 0 .and. self%have_prev) then
            self%slot = modulo(self%slot, self%memory) + 1; mk = min(self%stored + 1, self%memory)
        end if
    end function anderson_begin

    !> The same point evaluated again (its map changed): the slot it wrote is written anew
    subroutine anderson_again(self, mk)
        class(anderson_t), intent(inout) :: self
        integer, intent(in) :: mk
        if (mk > 0) self%slot = modulo(self%slot - 2, self%memory) + 1
    end subroutine anderson_again

    !> The columns pass at the point z with the residual `src` (or, with `law`, the
    !> Douglas-Rachford reflection of x = `src` through the contact law's proximal map): the sums
    !> over the grid `part` = [|f|^2, dF_k.dF_slot, dF_k.f] (1 + 2 mk), and with `law` the largest |x|
    !> where y is out of contact and |f| where it is in contact
    subroutine anderson_columns_step(self, src, z, mk, part, rp, rg, law)
        class(anderson_t), intent(inout) :: self
        type(rarray_t), intent(in) :: src, z
        integer, intent(in) :: mk
        real(dp), intent(out) :: part(:), rp, rg
        type(contact_law_t), intent(in), optional :: law
        call anderson_columns(src, z, self%df, self%gm, self%zprev, self%fprev, self%slot, mk, self%rows, rp, rg, &
                              law)
        call ordered_sum(self%grid, self%rows(1:1 + 2*mk, :), part(1:1 + 2*mk))
    end subroutine anderson_columns_step

    !> The mixing coefficients from the products `part` of the columns pass: the Gram matrix's new
    !> row and the least-squares problem. Returns the columns the update takes (0 when the problem
    !> is singular: the plain step, and the history restarts)
    integer function anderson_mix(self, part, mk, coef) result(mk_used)
        class(anderson_t), intent(inout) :: self
        real(dp), intent(in) :: part(:)
        integer, intent(in) :: mk
        real(dp), intent(out) :: coef(:)
        integer :: info
        info = 1
        coef = 0.0_dp
        if (mk > 0) then
            self%gram(1:mk, self%slot) = part(2:1 + mk); self%gram(self%slot, 1:mk) = part(2:1 + mk)
            call anderson_coefficients(self%gram, mk, part(2 + mk:1 + 2*mk), coef, info)
        end if
        if (info /= 0) then
            mk_used = 0; self%stored = 0
        else
            mk_used = mk; self%stored = mk
        end if
    end function anderson_mix

    !> z <- z + f - G c with the first mk columns (f given, or with `law` the reflection of
    !> x = `src` through the law's proximal map, x then becoming the new z), keeping (z, f) as the
    !> previous point
    subroutine anderson_update_step(self, src, z, coef, mk, law)
        class(anderson_t), intent(inout) :: self
        type(rarray_t), intent(inout) :: src, z
        real(dp), intent(in) :: coef(:)
        integer, intent(in) :: mk
        type(contact_law_t), intent(in), optional :: law
        call anderson_update(src, z, self%gm, self%zprev, self%fprev, coef, mk, law)
        self%have_prev = .true.
    end subroutine anderson_update_step

    !> One step from (z, f = residual at z): z <- z + f - G c. Returns .true. when the step was
    !> accelerated (a history existed and the least-squares problem was solved)
    function step_fields(self, z, f) result(accelerated)
        class(anderson_t), intent(inout) :: self
        type(rarray_t), intent(inout) :: z, f
        logical :: accelerated
        real(dp) :: coef(max(self%memory, 1)), part(1 + 2*max(self%memory, 1)), rp, rg
        integer :: mk
        mk = self%begin()
        call self%columns(f, z, mk, part, rp, rg)
        mk = self%mix(part, mk, coef)
        call self%update(f, z, coef, mk)
        accelerated = mk > 0
    end function step_fields

    !> The same on a host array of unknowns (one row)
    function step_arrays(self, z, f) result(accelerated)
        class(anderson_t), intent(inout) :: self
        real(dp), intent(inout), target, contiguous :: z(:), f(:)
        logical :: accelerated
        type(rarray_t) :: zh, fh
        zh%h(1:size(z), 1:1) => z; zh%n1 = size(z); zh%n2 = 1
        fh%h(1:size(f), 1:1) => f; fh%n1 = size(f); fh%n2 = 1
        accelerated = self%step(zh, fh)
    end function step_arrays

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
    !> accelerated step), and the history cleared; z a host array of unknowns
    subroutine anderson_plain_previous(self, z)
        class(anderson_t), intent(inout) :: self
        real(dp), intent(inout) :: z(:)
        z = reshape(self%zprev%h, [size(z)]) + reshape(self%fprev%h, [size(z)])
        call self%reset()
    end subroutine anderson_plain_previous

end module veslide_anderson
