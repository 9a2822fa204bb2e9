!> The small passes every solver shares: fills, scalings, copies, row sums, and the spectral
!> products of a Fourier multiplier. Each is a dispatcher on the arrays' backend (veslide_arrays):
!> its CPU twin here (`*_cpu`: explicit arrays, OpenMP over rows, the same arithmetic as the array
!> expressions they replaced) or its CUDA twin (src/grid/veslide_passes.cu: the same arguments,
!> the arrays as device memory). Row sums come back as one partial per row, which the caller adds
!> in order (veslide_collective), on either backend. A CUDA twin that fails leaves the error for
!> `device_check` (the solvers look between iterations).
module veslide_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long
    use, intrinsic :: iso_fortran_env, only: i8 => int64
    use veslide_kinds, only: dp
    use veslide_arrays, only: rarray_t, carray_t, elements
    use veslide_device, only: device_zero
    use veslide_threads, only: threaded
    implicit none
    private
    public :: fill, scale, divide, subtract, scaled_copy, divided_copy, centre_scale, centre_divide
    public :: row_sums, count_below, complex_scale, complex_add, complex_divide, zero_mean_mode
    public :: multiply_spectrum

    !> Modes of the CUDA twins that share a kernel (veslide_passes.cu)
    integer(c_int), parameter :: SCALE_MUL = 0, SCALE_DIV = 1, SCALE_SUB = 2
    integer(c_int), parameter :: COPY_MUL = 0, COPY_DIV = 1, COPY_CENTRE_MUL = 2, COPY_CENTRE_DIV = 3
    integer(c_int), parameter :: CX_MUL = 0, CX_DIV = 1, CX_ADD = 2

#ifdef VESLIDE_CUDA
    interface
        subroutine fill_gpu(n, a, v) bind(c, name='veslide_pass_fill')
            import :: c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: a
            real(c_double), value :: v
        end subroutine fill_gpu
        subroutine scale_gpu(n, a, s, mode) bind(c, name='veslide_pass_scale')
            import :: c_int, c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: a
            real(c_double), value :: s
            integer(c_int), value :: mode
        end subroutine scale_gpu
        subroutine copy_gpu(n, dst, src, c, s, mode) bind(c, name='veslide_pass_copy')
            import :: c_int, c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: dst, src
            real(c_double), value :: c, s
            integer(c_int), value :: mode
        end subroutine copy_gpu
        subroutine row_sums_gpu(nx, ny, a, rows) bind(c, name='veslide_pass_row_sums')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: a
            real(c_double), intent(out) :: rows(*)
        end subroutine row_sums_gpu
        subroutine count_below_gpu(nx, ny, a, v, rows) bind(c, name='veslide_pass_count_below')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: a
            real(c_double), value :: v
            real(c_double), intent(out) :: rows(*)
        end subroutine count_below_gpu
        subroutine complex_gpu(n, c, d, s, mode) bind(c, name='veslide_pass_complex')
            import :: c_int, c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: c, d
            real(c_double), value :: s
            integer(c_int), value :: mode
        end subroutine complex_gpu
        subroutine multiply_gpu(n, k, m, c) bind(c, name='veslide_pass_multiply')
            import :: c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: k, m
            real(c_double), value :: c
        end subroutine multiply_gpu
    end interface
#endif

contains



    ! ---- dispatchers --------------------------------------------------------------------

    !> a = v
    subroutine fill(a, v)
        type(rarray_t), intent(inout) :: a
        real(dp), intent(in) :: v
#ifdef VESLIDE_CUDA
        if (a%device) then
            call fill_gpu(elements(a), a%d, v); return
        end if
#endif
        call fill_cpu(a%h, v)
    end subroutine fill

    !> a = s a
    subroutine scale(a, s)
        type(rarray_t), intent(inout) :: a
        real(dp), intent(in) :: s
        call scale_by(a, s, SCALE_MUL)
    end subroutine scale

    !> a = a/s
    subroutine divide(a, s)
        type(rarray_t), intent(inout) :: a
        real(dp), intent(in) :: s
        call scale_by(a, s, SCALE_DIV)
    end subroutine divide

    !> a = a - s
    subroutine subtract(a, s)
        type(rarray_t), intent(inout) :: a
        real(dp), intent(in) :: s
        call scale_by(a, s, SCALE_SUB)
    end subroutine subtract

    subroutine scale_by(a, s, mode)
        type(rarray_t), intent(inout) :: a
        real(dp), intent(in) :: s
        integer(c_int), intent(in) :: mode
#ifdef VESLIDE_CUDA
        if (a%device) then
            call scale_gpu(elements(a), a%d, s, mode); return
        end if
#endif
        call scale_cpu(a%h, s, mode)
    end subroutine scale_by

    !> dst = s src
    subroutine scaled_copy(dst, src, s)
        type(rarray_t), intent(inout) :: dst
        type(rarray_t), intent(in) :: src
        real(dp), intent(in) :: s
        call copy(dst, src, 0.0_dp, s, COPY_MUL)
    end subroutine scaled_copy

    !> dst = src/s
    subroutine divided_copy(dst, src, s)
        type(rarray_t), intent(inout) :: dst
        type(rarray_t), intent(in) :: src
        real(dp), intent(in) :: s
        call copy(dst, src, 0.0_dp, s, COPY_DIV)
    end subroutine divided_copy

    !> dst = (src - c) s
    subroutine centre_scale(dst, src, c, s)
        type(rarray_t), intent(inout) :: dst
        type(rarray_t), intent(in) :: src
        real(dp), intent(in) :: c, s
        call copy(dst, src, c, s, COPY_CENTRE_MUL)
    end subroutine centre_scale

    !> dst = (src - c)/s
    subroutine centre_divide(dst, src, c, s)
        type(rarray_t), intent(inout) :: dst
        type(rarray_t), intent(in) :: src
        real(dp), intent(in) :: c, s
        call copy(dst, src, c, s, COPY_CENTRE_DIV)
    end subroutine centre_divide

    subroutine copy(dst, src, c, s, mode)
        type(rarray_t), intent(inout) :: dst
        type(rarray_t), intent(in) :: src
        real(dp), intent(in) :: c, s
        integer(c_int), intent(in) :: mode
#ifdef VESLIDE_CUDA
        if (dst%device) then
            call copy_gpu(elements(dst), dst%d, src%d, c, s, mode); return
        end if
#endif
        call copy_cpu(dst%h, src%h, c, s, mode)
    end subroutine copy

    !> rows(j) = the sum of row j of a
    subroutine row_sums(a, rows)
        type(rarray_t), intent(in) :: a
        real(dp), intent(out) :: rows(:)
#ifdef VESLIDE_CUDA
        if (a%device) then
            call row_sums_gpu(a%n1, a%n2, a%d, rows); return
        end if
#endif
        call row_sums_cpu(a%h, rows)
    end subroutine row_sums

    !> The number of entries of a below v (this process's)
    integer(i8) function count_below(a, v) result(n)
        type(rarray_t), intent(in) :: a
        real(dp), intent(in) :: v
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: rows(:)
        if (a%device) then
            allocate (rows(a%n2))
            call count_below_gpu(a%n1, a%n2, a%d, v, rows)
            n = nint(sum(rows), i8)
            return
        end if
#endif
        n = count(a%h < v, kind=i8)
    end function count_below

    !> c = s c
    subroutine complex_scale(c, s)
        type(carray_t), intent(inout) :: c
        real(dp), intent(in) :: s
#ifdef VESLIDE_CUDA
        if (c%device) then
            call complex_gpu(elements(c), c%d, c%d, s, CX_MUL); return
        end if
#endif
        call complex_scale_cpu(c%h, s)
    end subroutine complex_scale

    !> c = c/s
    subroutine complex_divide(c, s)
        type(carray_t), intent(inout) :: c
        real(dp), intent(in) :: s
#ifdef VESLIDE_CUDA
        if (c%device) then
            call complex_gpu(elements(c), c%d, c%d, s, CX_DIV); return
        end if
#endif
        call complex_divide_cpu(c%h, s)
    end subroutine complex_divide

    !> c = c + d
    subroutine complex_add(c, d)
        type(carray_t), intent(inout) :: c
        type(carray_t), intent(in) :: d
#ifdef VESLIDE_CUDA
        if (c%device) then
            call complex_gpu(elements(c), c%d, d%d, 0.0_dp, CX_ADD); return
        end if
#endif
        call complex_add_cpu(c%h, d%h)
    end subroutine complex_add

    !> c(1, 1) = 0: the mean mode of a spectrum held on one process
    subroutine zero_mean_mode(c)
        type(carray_t), intent(inout) :: c
        if (c%device) then
            call device_zero(c%d, 16_i8)
        else
            c%h(1, 1) = (0.0_dp, 0.0_dp)
        end if
    end subroutine zero_mean_mode

    !> k = k (m c): a Fourier multiplier m with a real factor c (one fused pass)
    subroutine multiply_spectrum(k, m, c)
        type(carray_t), intent(inout) :: k
        type(carray_t), intent(in) :: m
        real(dp), intent(in) :: c
#ifdef VESLIDE_CUDA
        if (k%device) then
            call multiply_gpu(elements(k), k%d, m%d, c); return
        end if
#endif
        call multiply_cpu(k%h, m%h, c)
    end subroutine multiply_spectrum

    ! ---- CPU twins ----------------------------------------------------------------------

    subroutine fill_cpu(a, v)
        real(dp), intent(out) :: a(:, :)
        real(dp), intent(in) :: v
        integer :: j
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2)))
        do j = 1, size(a, 2)
            a(:, j) = v
        end do
        !$omp end parallel do
    end subroutine fill_cpu

    subroutine scale_cpu(a, s, mode)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(in) :: s
        integer(c_int), intent(in) :: mode
        integer :: j
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2)))
        do j = 1, size(a, 2)
            select case (mode)
            case (SCALE_MUL); a(:, j) = s*a(:, j)
            case (SCALE_DIV); a(:, j) = a(:, j)/s
            case default; a(:, j) = a(:, j) - s
            end select
        end do
        !$omp end parallel do
    end subroutine scale_cpu

    subroutine copy_cpu(dst, src, c, s, mode)
        real(dp), intent(out) :: dst(:, :)
        real(dp), intent(in) :: src(:, :)
        real(dp), intent(in) :: c, s
        integer(c_int), intent(in) :: mode
        integer :: j
        !$omp parallel do schedule(static) if (threaded(size(dst), size(dst, 2)))
        do j = 1, size(dst, 2)
            select case (mode)
            case (COPY_MUL); dst(:, j) = s*src(:, j)
            case (COPY_DIV); dst(:, j) = src(:, j)/s
            case (COPY_CENTRE_MUL); dst(:, j) = (src(:, j) - c)*s
            case default; dst(:, j) = (src(:, j) - c)/s
            end select
        end do
        !$omp end parallel do
    end subroutine copy_cpu

    subroutine row_sums_cpu(a, rows)
        real(dp), intent(in) :: a(:, :)
        real(dp), intent(out) :: rows(:)
        integer :: j
        !$omp parallel do schedule(guided) if (threaded(size(a), size(a, 2)))
        do j = 1, size(a, 2)
            rows(j) = sum(a(:, j))
        end do
        !$omp end parallel do
    end subroutine row_sums_cpu

    subroutine complex_scale_cpu(c, s)
        complex(dp), intent(inout) :: c(:, :)
        real(dp), intent(in) :: s
        integer :: j
        !$omp parallel do schedule(static) if (threaded(2*size(c), size(c, 2)))
        do j = 1, size(c, 2)
            c(:, j) = s*c(:, j)
        end do
        !$omp end parallel do
    end subroutine complex_scale_cpu

    subroutine complex_divide_cpu(c, s)
        complex(dp), intent(inout) :: c(:, :)
        real(dp), intent(in) :: s
        integer :: j
        !$omp parallel do schedule(static) if (threaded(2*size(c), size(c, 2)))
        do j = 1, size(c, 2)
            c(:, j) = c(:, j)/s
        end do
        !$omp end parallel do
    end subroutine complex_divide_cpu

    subroutine complex_add_cpu(c, d)
        complex(dp), intent(inout) :: c(:, :)
        complex(dp), intent(in) :: d(:, :)
        integer :: j
        !$omp parallel do schedule(static) if (threaded(2*size(c), size(c, 2)))
        do j = 1, size(c, 2)
            c(:, j) = c(:, j) + d(:, j)
        end do
        !$omp end parallel do
    end subroutine complex_add_cpu

    subroutine multiply_cpu(k, m, c)
        complex(dp), intent(inout) :: k(:, :)
        complex(dp), intent(in) :: m(:, :)
        real(dp), intent(in) :: c
        integer :: i, j
        do j = 1, size(k, 2)
            do i = 1, size(k, 1)
                k(i, j) = k(i, j)*(m(i, j)*c)
            end do
        end do
    end subroutine multiply_cpu

end module veslide_passes
