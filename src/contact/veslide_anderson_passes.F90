!> The two passes of Anderson mixing (veslide_anderson), on either backend: the CPU twins here,
!> the CUDA twins in veslide_anderson_passes.cu (memory m of at most `device_max_memory` there).
!> The residual f of the fixed-point map is either given (no contact law: the array `src`), or
!> the Douglas-Rachford reflection of the resolvent's output x = `src` and the iterate z through
!> the contact law's proximal map (a law given: y = prox(2x - z), the hard wall's max(2x - z, 0);
!> f = y - x, never stored), the law chosen once per call (the CPU twin's maps; the CUDA functors'
!> template argument, vs::with_law).
!>  columns  per row |f|^2, and with mk > 0 the new history columns dF = f - f_prev and
!>           G = (z - z_prev) + dF in slot `slot` (single precision) with their products
!>           dF_k.dF_slot and dF_k.f, k = 1..mk; reflecting, max |x| where y is out of contact
!>           (rp) and max |f| where it is in contact (rg)
!>  update   z <- z + f - G c, keeping (z, f) as the previous point; reflecting, x = the new z
!>           (the next map's input)
!> Unknowns are the rows of a field (n1, n2), row by row: the per-row partials are added in order
!> by the caller, so the mixing is the same on any number of threads or processes.
module veslide_anderson_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long
    use, intrinsic :: iso_fortran_env, only: real32
    use veslide_kinds, only: dp
    use veslide_arrays, only: rarray_t, sarray_t, elements
    use veslide_contact_law, only: contact_law_t, LAW_HARD_WALL
    use veslide_threads, only: threaded
    implicit none
    private
    public :: anderson_columns, anderson_update, device_max_memory

    !> The largest memory the CUDA twins take (their sums are fixed at compile time)
    integer, parameter :: device_max_memory = 8

#ifdef VESLIDE_CUDA
    interface
        !> rows(1 + 2 mk + 2, ny): [|f|^2, dF_k.dF_slot, dF_k.f, min -|x| (y out of contact),
        !> min -|f| (y in contact)]
        subroutine columns_gpu(law, param, nx, ny, src, z, df, gm, zprev, fprev, slot, mk, history, reflect, rows) &
            bind(c, name='veslide_anderson_columns')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: law
            real(c_double), intent(in) :: param(*)
            integer(c_int), value :: nx, ny, slot, mk, history, reflect
            type(c_ptr), value :: src, z, df, gm, zprev, fprev
            real(c_double), intent(out) :: rows(*)
        end subroutine columns_gpu
        subroutine update_gpu(law, param, n, src, z, gm, zprev, fprev, coef, mk, reflect) &
            bind(c, name='veslide_anderson_update')
            import :: c_long, c_int, c_ptr, c_double
            integer(c_int), value :: law
            real(c_double), intent(in) :: param(*)
            integer(c_long), value :: n
            type(c_ptr), value :: src, z, gm, zprev, fprev
            real(c_double), intent(in) :: coef(*)
            integer(c_int), value :: mk, reflect
        end subroutine update_gpu
    end interface
#endif

contains

    !> The residual's norm per row and, with mk > 0, the new history column `slot` with its
    !> products; rows(1 + 2 mk, n2) the per-row partials; rp, rg when reflecting through `law`
    !> (else 0)
    subroutine anderson_columns(src, z, df, gm, zprev, fprev, slot, mk, rows, rp, rg, law)
        type(rarray_t), intent(in) :: src, z, zprev, fprev
        type(sarray_t), intent(inout) :: df, gm
        integer, intent(in) :: slot, mk
        real(dp), intent(out) :: rows(:, :), rp, rg
        !> the contact law to reflect through (absent: f given in `src`)
        type(contact_law_t), intent(in), optional :: law
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        type(contact_law_t) :: l
        if (z%device) then
            if (present(law)) l = law
            allocate (out(3 + 2*mk, z%n2))
            call columns_gpu(l%kind, l%param, z%n1, z%n2, src%d, z%d, df%d, gm%d, zprev%d, fprev%d, slot, mk, df%n1, &
                             merge(1_c_int, 0_c_int, present(law)), out)
            rows(1:1 + 2*mk, :) = out(1:1 + 2*mk, :)
            rp = max(0.0_dp, -minval(out(2 + 2*mk, :))); rg = max(0.0_dp, -minval(out(3 + 2*mk, :)))
            return
        end if
#endif
        if (.not. present(law)) then
            call columns_cpu(z%n1, z%n2, src%h, z%h, df%h, gm%h, zprev%h, fprev%h, slot, mk, .false., rows, rp, rg)
            return
        end if
        select case (law%kind)
        case (LAW_HARD_WALL)      ! (columns_cpu reflects through the hard wall's maps)
            call columns_cpu(z%n1, z%n2, src%h, z%h, df%h, gm%h, zprev%h, fprev%h, slot, mk, .true., rows, rp, rg)
        case default
            error stop "veslide:anderson_passes:anderson_columns: a contact law this pass does not take"
        end select
    end subroutine anderson_columns

    !> z <- z + f - G c (f given, or the reflection of src = x and z through `law`), keeping (z, f)
    !> as the previous point; reflecting, x = the new z
    subroutine anderson_update(src, z, gm, zprev, fprev, coef, mk, law)
        type(rarray_t), intent(inout) :: src, z, zprev, fprev
        type(sarray_t), intent(in) :: gm
        real(dp), intent(in) :: coef(:)
        integer, intent(in) :: mk
        !> the contact law to reflect through (absent: f given in `src`)
        type(contact_law_t), intent(in), optional :: law
#ifdef VESLIDE_CUDA
        type(contact_law_t) :: l
        if (z%device) then
            if (present(law)) l = law
            call update_gpu(l%kind, l%param, elements(z), src%d, z%d, gm%d, zprev%d, fprev%d, coef, mk, &
                            merge(1_c_int, 0_c_int, present(law)))
            return
        end if
#endif
        if (.not. present(law)) then
            call update_cpu(elements(z), src%h, z%h, gm%h, zprev%h, fprev%h, coef, mk, .false.)
            return
        end if
        select case (law%kind)
        case (LAW_HARD_WALL)      ! (update_cpu reflects through the hard wall's maps)
            call update_cpu(elements(z), src%h, z%h, gm%h, zprev%h, fprev%h, coef, mk, .true.)
        case default
            error stop "veslide:anderson_passes:anderson_update: a contact law this pass does not take"
        end select
    end subroutine anderson_update

    ! ---- CPU twins: with `reflect`, through the hard wall's maps (another law's reflection
    ! would be another pair, chosen by the dispatchers above) --------------------------------

    subroutine columns_cpu(nx, ny, src, z, df, gm, zprev, fprev, slot, mk, reflect, rows, rp, rg)
        integer, intent(in) :: nx, ny, slot, mk
        real(dp), intent(in) :: src(nx*ny), z(nx*ny), zprev(nx*ny), fprev(nx*ny)
        real(real32), intent(inout) :: df(:, :), gm(:, :)
        logical, intent(in) :: reflect
        real(dp), intent(out) :: rows(:, :), rp, rg
        real(dp) :: xv, zv, yv, fv, dfv, part(1 + 2*max(mk, 1))
        integer :: i, j, k
        rp = 0.0_dp; rg = 0.0_dp
        !$omp parallel do schedule(guided) if (threaded(nx*ny, ny)) &
        !$omp& private(i, xv, zv, yv, fv, dfv, k, part) reduction(max:rp, rg)
        do j = 1, ny
            part(1:1 + 2*mk) = 0.0_dp
            do i = (j - 1)*nx + 1, j*nx
                zv = z(i)
                if (reflect) then
                    xv = src(i)
                    yv = hard_wall_project(2.0_dp*xv - zv)
                    fv = yv - xv
                    if (hard_wall_in_contact(yv)) then
                        rg = max(rg, abs(fv))
                    else
                        rp = max(rp, abs(xv))
                    end if
                else
                    fv = src(i)
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
    end subroutine columns_cpu

    subroutine update_cpu(n, src, z, gm, zprev, fprev, coef, mk, reflect)
        integer(c_long), intent(in) :: n
        real(dp), intent(inout) :: src(n), z(n), zprev(n), fprev(n)
        real(real32), intent(in) :: gm(:, :)
        real(dp), intent(in) :: coef(:)
        integer, intent(in) :: mk
        logical, intent(in) :: reflect
        real(dp) :: xv, zv, fv, zn
        integer :: i, k
        !$omp parallel do schedule(guided) if (threaded(int(n), 2)) private(xv, zv, fv, zn, k)
        do i = 1, int(n)
            zv = z(i)
            if (reflect) then
                xv = src(i)
                fv = hard_wall_project(2.0_dp*xv - zv) - xv
            else
                fv = src(i)
            end if
            zn = zv + fv
            do k = 1, mk
                zn = zn - real(gm(i, k), dp)*coef(k)
            end do
            zprev(i) = zv; fprev(i) = fv
            z(i) = zn
            if (reflect) src(i) = zn
        end do
        !$omp end parallel do
    end subroutine update_cpu

    include 'veslide_contact_law_maps.inc'

end module veslide_anderson_passes
