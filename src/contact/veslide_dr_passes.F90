!> The fused passes of the splitting with Anderson mixing (veslide_solver_dr), on either backend:
!> each a dispatcher on the arrays' backend, its CPU twin here (`*_cpu`: the loops of the solver
!> as they were, on the fields flattened to n = nx ny unknowns, row by row) and its CUDA twin in
!> veslide_dr_passes.cu (memory m of at most `device_max_memory` there).
!>  map        y = max(2x - z, 0), f = y - x: per row |f|^2, and the new history columns
!>             dF = f - f_prev, G = (z - z_prev) + dF (slot `slot` of m, single precision) with
!>             their products dF_k.dF_slot and dF_k.f for k = 1..mk; max |x| where y = 0 (rp)
!>             and max |f| where y > 0 (rg)
!>  update     z <- z + f - G c, keeping (z, f) as the previous point; x = the new z
!>  rebalance  z = y + s (z - y) (z remapped to a step s times larger); x = z
!>  project    p = p_mean max(2x - z, 0)
!>  restore    z = z_prev + f_prev; x = z
!>  add_gap    z = z + gamma g/hs
module veslide_dr_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long
    use, intrinsic :: iso_fortran_env, only: real32
    use veslide_kinds, only: dp
    use veslide_arrays, only: rarray_t, sarray_t, elements
    implicit none
    private
    public :: dr_map, dr_update, dr_rebalance, dr_project, dr_restore, dr_add_gap, device_max_memory

    !> The largest Anderson memory the CUDA twins take (their sums are fixed at compile time)
    integer, parameter :: device_max_memory = 8

#ifdef VESLIDE_CUDA
    interface
        !> rows(1 + 2 mk + 2, ny): [|f|^2, dF_k.dF_slot, dF_k.f, min -|x| (y = 0), min -|f| (y > 0)]
        subroutine map_gpu(nx, ny, x, z, df, gm, zprev, fprev, slot, mk, history, rows) bind(c, name='veslide_dr_map')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny, slot, mk, history
            type(c_ptr), value :: x, z, df, gm, zprev, fprev
            real(c_double), intent(out) :: rows(*)
        end subroutine map_gpu
        subroutine update_gpu(n, x, z, gm, zprev, fprev, coef, mk) bind(c, name='veslide_dr_update')
            import :: c_long, c_int, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: x, z, gm, zprev, fprev
            real(c_double), intent(in) :: coef(*)
            integer(c_int), value :: mk
        end subroutine update_gpu
        !> mode 0: rebalance (s), 1: project (s = p_mean, into p), 2: restore, 3: add_gap (x = g, s = gamma/hs pair)
        subroutine elementwise_gpu(n, mode, x, z, p, a, b, s, t) bind(c, name='veslide_dr_elementwise')
            import :: c_long, c_int, c_ptr, c_double
            integer(c_long), value :: n
            integer(c_int), value :: mode
            type(c_ptr), value :: x, z, p, a, b
            real(c_double), value :: s, t
        end subroutine elementwise_gpu
    end interface
#endif

contains


    ! ---- dispatchers --------------------------------------------------------------------

    !> The map and, with mk > 0, the new history column `slot` with its products (see above);
    !> rows(1 + 2 mk, ny) the per-row partials
    subroutine dr_map(x, z, df, gm, zprev, fprev, slot, mk, rows, rp, rg)
        type(rarray_t), intent(in) :: x, z, zprev, fprev
        type(sarray_t), intent(inout) :: df, gm
        integer, intent(in) :: slot, mk
        real(dp), intent(out) :: rows(:, :), rp, rg
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (x%device) then
            allocate (out(3 + 2*mk, x%n2))
            call map_gpu(x%n1, x%n2, x%d, z%d, df%d, gm%d, zprev%d, fprev%d, slot, mk, df%n1, out)
            rows(1:1 + 2*mk, :) = out(1:1 + 2*mk, :)
            rp = max(0.0_dp, -minval(out(2 + 2*mk, :))); rg = max(0.0_dp, -minval(out(3 + 2*mk, :)))
            return
        end if
#endif
        call dr_map_cpu(x%n1, x%n2, x%h, z%h, df%h, gm%h, zprev%h, fprev%h, slot, mk, rows, rp, rg)
    end subroutine dr_map

    !> z <- z + f - G c (f from x and z), keeping (z, f) as the previous point; x = the new z
    subroutine dr_update(x, z, gm, zprev, fprev, coef, mk)
        type(rarray_t), intent(inout) :: x, z, zprev, fprev
        type(sarray_t), intent(in) :: gm
        real(dp), intent(in) :: coef(:)
        integer, intent(in) :: mk
#ifdef VESLIDE_CUDA
        if (x%device) then
            call update_gpu(elements(x), x%d, z%d, gm%d, zprev%d, fprev%d, coef, mk); return
        end if
#endif
        call dr_update_cpu(elements(x), x%h, z%h, gm%h, zprev%h, fprev%h, coef, mk)
    end subroutine dr_update

    !> z = y + s (z - y), y = max(2x - z, 0); x = z
    subroutine dr_rebalance(x, z, s)
        type(rarray_t), intent(inout) :: x, z
        real(dp), intent(in) :: s
#ifdef VESLIDE_CUDA
        if (x%device) then
            call elementwise_gpu(elements(x), 0_c_int, x%d, z%d, z%d, z%d, z%d, s, 0.0_dp); return
        end if
#endif
        call dr_rebalance_cpu(elements(x), x%h, z%h, s)
    end subroutine dr_rebalance

    !> p = p_mean max(2x - z, 0)
    subroutine dr_project(p, x, z, p_mean)
        type(rarray_t), intent(inout) :: p
        type(rarray_t), intent(in) :: x, z
        real(dp), intent(in) :: p_mean
#ifdef VESLIDE_CUDA
        if (p%device) then
            call elementwise_gpu(elements(p), 1_c_int, x%d, z%d, p%d, p%d, p%d, p_mean, 0.0_dp); return
        end if
#endif
        p%h = p_mean*max(2.0_dp*x%h - z%h, 0.0_dp)
    end subroutine dr_project

    !> z = z_prev + f_prev; x = z
    subroutine dr_restore(x, z, zprev, fprev)
        type(rarray_t), intent(inout) :: x, z
        type(rarray_t), intent(in) :: zprev, fprev
#ifdef VESLIDE_CUDA
        if (x%device) then
            call elementwise_gpu(elements(x), 2_c_int, x%d, z%d, z%d, zprev%d, fprev%d, 0.0_dp, 0.0_dp); return
        end if
#endif
        call dr_restore_cpu(elements(x), x%h, z%h, zprev%h, fprev%h)
    end subroutine dr_restore

    !> z = z + gamma g/hs
    subroutine dr_add_gap(z, g, gamma, hs)
        type(rarray_t), intent(inout) :: z
        type(rarray_t), intent(in) :: g
        real(dp), intent(in) :: gamma, hs
#ifdef VESLIDE_CUDA
        if (z%device) then
            call elementwise_gpu(elements(z), 3_c_int, g%d, z%d, z%d, z%d, z%d, gamma, hs); return
        end if
#endif
        z%h = z%h + gamma*g%h/hs
    end subroutine dr_add_gap

    ! ---- CPU twins ----------------------------------------------------------------------

    subroutine dr_map_cpu(nx, ny, xb, z, df, gm, zprev, fprev, slot, mk, rows, rp, rg)
        integer, intent(in) :: nx, ny, slot, mk
        real(dp), intent(in) :: xb(nx*ny), z(nx*ny), zprev(nx*ny), fprev(nx*ny)
        real(real32), intent(inout) :: df(:, :), gm(:, :)
        real(dp), intent(out) :: rows(:, :), rp, rg
        real(dp) :: xv, zv, yv, fv, dfv, part(1 + 2*max(mk, 1))
        integer :: i, j, k
        rp = 0.0_dp; rg = 0.0_dp
        !$omp parallel do schedule(guided) private(i, xv, zv, yv, fv, dfv, k, part) reduction(max:rp, rg)
        do j = 1, ny
            part(1:1 + 2*mk) = 0.0_dp
            do i = (j - 1)*nx + 1, j*nx
                xv = xb(i); zv = z(i)
                yv = max(2.0_dp*xv - zv, 0.0_dp)
                fv = yv - xv
                if (yv > 0.0_dp) then
                    rg = max(rg, abs(fv))
                else
                    rp = max(rp, abs(xv))
                end if
                part(1) = part(1) + fv**2
                if (mk > 0) then
                    df(i, slot) = real(fv - fprev(i), real32)
                    gm(i, slot) = real((zv - zprev(i)) + (fv - fprev(i)), real32)
                    dfv = real(df(i, slot), dp)
                    do k = 1, mk
                        part(1 + k) = part(1 + k) + real(df(i, k), dp)*dfv
                        part(1 + mk + k) = part(1 + mk + k) + real(df(i, k), dp)*fv
                    end do
                end if
            end do
            rows(1:1 + 2*mk, j) = part(1:1 + 2*mk)
        end do
        !$omp end parallel do
    end subroutine dr_map_cpu

    subroutine dr_update_cpu(n, xb, z, gm, zprev, fprev, coef, mk)
        integer(c_long), intent(in) :: n
        real(dp), intent(inout) :: xb(n), z(n), zprev(n), fprev(n)
        real(real32), intent(in) :: gm(:, :)
        real(dp), intent(in) :: coef(:)
        integer, intent(in) :: mk
        real(dp) :: xv, zv, fv, zn
        integer :: i, k
        !$omp parallel do schedule(guided) private(xv, zv, fv, zn, k)
        do i = 1, int(n)
            xv = xb(i); zv = z(i)
            fv = max(2.0_dp*xv - zv, 0.0_dp) - xv
            zn = zv + fv
            do k = 1, mk
                zn = zn - real(gm(i, k), dp)*coef(k)
            end do
            zprev(i) = zv; fprev(i) = fv
            z(i) = zn
            xb(i) = zn
        end do
        !$omp end parallel do
    end subroutine dr_update_cpu

    subroutine dr_rebalance_cpu(n, xb, z, s)
        integer(c_long), intent(in) :: n
        real(dp), intent(inout) :: xb(n), z(n)
        real(dp), intent(in) :: s
        real(dp) :: yv
        integer :: i
        !$omp parallel do schedule(guided) private(yv)
        do i = 1, int(n)
            yv = max(2.0_dp*xb(i) - z(i), 0.0_dp)
            z(i) = yv + s*(z(i) - yv)
            xb(i) = z(i)
        end do
        !$omp end parallel do
    end subroutine dr_rebalance_cpu

    subroutine dr_restore_cpu(n, xb, z, zprev, fprev)
        integer(c_long), intent(in) :: n
        real(dp), intent(inout) :: xb(n), z(n)
        real(dp), intent(in) :: zprev(n), fprev(n)
        z = zprev + fprev
        xb = z
    end subroutine dr_restore_cpu

end module veslide_dr_passes
