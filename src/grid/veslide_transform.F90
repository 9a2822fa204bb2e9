!> The FFT of a solve, where the solve runs: on the host the caller's `fft2d_t` (FFTW; its
!> buffers viewed, not copied), on the device its cuFFT twin (src/grid/veslide_transform.cu),
!> with the same buffers and the same conventions: `x` the real field (nx, ny), `k` its
!> half-spectrum (nx/2+1, ny), `forward` x -> k unnormalised (x is not to be read afterwards),
!> `backward_unscaled` k -> x without 1/(nx ny) (k is destroyed). On the device, cuFFT's work area
!> (scratch while a transform runs) is an array the caller lends (`lend_work`: one that is dead
!> whenever a transform runs), else the transform's own, allocated at its first use.
module veslide_transform
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int, c_double, c_associated
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_arrays, only: rarray_t, carray_t
    use veslide_device, only: device_check
    implicit none
    private
    public :: transform_t

    type :: transform_t
        integer :: nx = 0, ny = 0
        logical :: device = .false.                   !! cuFFT on the device
        type(rarray_t) :: x                           !! real buffer
        type(carray_t) :: k                           !! half-spectrum buffer
        real(dp) :: work_bytes = 0.0_dp               !! device: cuFFT's work area [bytes]
        logical :: lent = .false.                     !! device: the work area is the caller's
        type(fft2d_t), pointer, private :: host => null()
        type(c_ptr), private :: plan = c_null_ptr
    contains
        procedure :: on_host => transform_on_host
        procedure :: on_device => transform_on_device
        procedure :: lend_work => transform_lend_work
        procedure :: forward => transform_forward
        procedure :: backward_unscaled => transform_backward_unscaled
        procedure :: destroy => transform_destroy
    end type transform_t

#ifdef VESLIDE_CUDA
    interface
        integer(c_int) function c_create(handle, nx, ny, x, k, policy, work_bytes) &
            bind(c, name='veslide_transform_create')
            import :: c_ptr, c_int, c_double
            type(c_ptr), intent(out) :: handle
            integer(c_int), value :: nx, ny, policy
            type(c_ptr), value :: x, k
            real(c_double), intent(out) :: work_bytes
        end function c_create
        integer(c_int) function c_lend(handle, area, bytes) bind(c, name='veslide_transform_lend_work')
            import :: c_ptr, c_int, c_double
            type(c_ptr), value :: handle, area
            real(c_double), value :: bytes
        end function c_lend
        integer(c_int) function c_forward(handle) bind(c, name='veslide_transform_forward')
            import :: c_ptr, c_int
            type(c_ptr), value :: handle
        end function c_forward
        integer(c_int) function c_backward(handle) bind(c, name='veslide_transform_backward')
            import :: c_ptr, c_int
            type(c_ptr), value :: handle
        end function c_backward
        integer(c_int) function c_destroy(handle) bind(c, name='veslide_transform_destroy')
            import :: c_ptr, c_int
            type(c_ptr), value :: handle
        end function c_destroy
    end interface
#endif

contains

    !> The transforms of `fft` (FFTW on the host), its buffers viewed
    subroutine transform_on_host(self, fft)
        class(transform_t), intent(inout) :: self
        type(fft2d_t), intent(inout), target :: fft
        call self%destroy()
        self%device = .false.
        self%nx = fft%nx; self%ny = fft%ny
        self%host => fft
        call self%x%view(fft%x)
        call self%k%view(fft%k)
    end subroutine transform_on_host

    !> Transforms of nx x ny on the device (buffers and cuFFT plans allocated there).
    !> `minimal_work`: cuFFT's smallest work area (true), its fastest plans (false); absent: as
    !> the environment's VESLIDE_CUFFT_WORKAREA says ('minimal' or 'performance', the default)
    subroutine transform_on_device(self, nx, ny, error, minimal_work)
        class(transform_t), intent(inout) :: self
        integer, intent(in) :: nx, ny
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: minimal_work
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat, policy
        policy = -1
        if (present(minimal_work)) policy = merge(1, 0, minimal_work)
        call self%destroy()
        if (nx < 2) then
            call fatal_error(error, "veslide:transform:on_device: the device's transforms need nx >= 2"); return
        end if
        self%device = .true.
        self%nx = nx; self%ny = ny
        call self%x%create(nx, ny, .true.)
        call self%k%create(nx/2 + 1, ny, .true.)
        call device_check(error, "veslide:transform:on_device"); if (allocated(error)) return
        stat = c_create(self%plan, int(nx, c_int), int(ny, c_int), self%x%d, self%k%d, policy, self%work_bytes)
        call device_check(error, "veslide:transform:on_device")
#else
        call fatal_error(error, "veslide:transform:on_device: this build has no device support (gpu/build.sh)")
#endif
    end subroutine transform_on_device

    !> On the device: cuFFT's work area in `a`'s memory from now on, which the caller does not
    !> read across a transform (what a transform leaves there is garbage; the emulated device
    !> writes NaN there), when `a` is large enough; without `a`, or when it is too small, the
    !> transform's own (allocated now: `work_bytes` more). `lent` says which. On the host: nothing.
    subroutine transform_lend_work(self, a)
        class(transform_t), intent(inout) :: self
        type(rarray_t), intent(in), optional :: a
#ifdef VESLIDE_CUDA
        if (.not. self%device) return
        if (present(a)) then
            self%lent = c_lend(self%plan, a%d, real(a%bytes, dp)) /= 0
        else
            self%lent = c_lend(self%plan, c_null_ptr, 0.0_dp) /= 0
        end if
#else
        if (present(a)) self%lent = .false.
#endif
    end subroutine transform_lend_work

    !> x -> k (unnormalised, exp(-i q.x))
    subroutine transform_forward(self)
        class(transform_t), intent(inout) :: self
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        if (self%device) then
            stat = c_forward(self%plan); return
        end if
#endif
        call self%host%forward()
    end subroutine transform_forward

    !> k -> x without the 1/(nx ny) factor (k destroyed)
    subroutine transform_backward_unscaled(self)
        class(transform_t), intent(inout) :: self
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        if (self%device) then
            stat = c_backward(self%plan); return
        end if
#endif
        call self%host%backward_unscaled()
    end subroutine transform_backward_unscaled

    !> Plans and device buffers freed; a host transform only forgets the caller's
    subroutine transform_destroy(self)
        class(transform_t), intent(inout) :: self
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        if (c_associated(self%plan)) stat = c_destroy(self%plan)
#endif
        self%plan = c_null_ptr
        call self%x%destroy()
        call self%k%destroy()
        nullify (self%host)
        self%device = .false.; self%nx = 0; self%ny = 0; self%work_bytes = 0.0_dp; self%lent = .false.
    end subroutine transform_destroy

end module veslide_transform
