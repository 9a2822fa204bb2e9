!> Two-dimensional real FFTs through FFTW 3's Fortran 2003 interface.
!>
!> One `fft2d_t` owns FFTW-aligned buffers `x` (nx, ny) and `k` (nx/2+1, ny) and the two plans
!> between them, made once and reused. `forward` is x -> k, `backward` is k -> x divided by nx*ny,
!> so backward(forward(x)) = x. Never assign an `fft2d_t`: the copy would share, then free, C memory.
module veslide_fftw
    use, intrinsic :: iso_c_binding
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: c_strlen
    implicit none
    private
#include "fftw3.f03"
    public :: fft2d_t, fft_planner_flag, fft_planner_names

    !> FFTW planner rigour by name (the namelist's `&solver fft_planner`)
    character(len=*), parameter :: fft_planner_names(3) = [character(len=8) :: 'estimate', 'measure', 'patient']

    type :: fft2d_t
        integer :: nx = 0, ny = 0
        type(c_ptr), private :: plan_r2c = c_null_ptr, plan_c2r = c_null_ptr
        type(c_ptr), private :: p_x = c_null_ptr, p_k = c_null_ptr
        !> real-space buffer, (nx, ny), FFTW-aligned
        real(c_double), pointer :: x(:, :) => null()
        !> half-spectrum buffer, (nx/2+1, ny), FFTW-aligned
        complex(c_double_complex), pointer :: k(:, :) => null()
    contains
        procedure :: init => fft_init
        procedure :: forward => fft_forward
        procedure :: backward => fft_backward
        procedure :: backward_unscaled => fft_backward_unscaled
        procedure :: destroy => fft_destroy
        final :: fft_finalize
    end type fft2d_t

    logical, save :: threads_ready = .false.

    interface
        subroutine c_free(p) bind(c, name='free')
            import :: c_ptr
            type(c_ptr), value :: p
        end subroutine c_free
    end interface

contains

    !> FFTW planner flag from its name: 'estimate', 'measure' or 'patient'
    integer function fft_planner_flag(name) result(flag)
        character(len=*), intent(in) :: name
        select case (name)
        case ('estimate'); flag = FFTW_ESTIMATE
        case ('patient'); flag = FFTW_PATIENT
        case default; flag = FFTW_MEASURE
        end select
    end function fft_planner_flag

    !> Allocate buffers and plan both transforms (buffers are overwritten by planning).
    !> `isolated` plans FFTW_ESTIMATE without the process's accumulated wisdom (and leaves that
    !> wisdom as it was): a one-off transform whose rounding is the same in every run, whatever
    !> other plans the process made before (used by the surface generator).
    subroutine fft_init(self, nx, ny, error, planner, nthreads, isolated)
        class(fft2d_t), intent(inout) :: self
        !> grid size
        integer, intent(in) :: nx, ny
        !> error on failure
        type(error_t), allocatable, intent(out) :: error
        !> FFTW planner flag name (default 'measure')
        character(len=*), intent(in), optional :: planner
        !> threads used by each transform (default 1)
        integer, intent(in), optional :: nthreads
        !> plan FFTW_ESTIMATE on one thread, ignoring wisdom (default .false.)
        logical, intent(in), optional :: isolated
        integer :: flag, nthreads_
        logical :: isolated_
        type(c_ptr) :: saved
        integer(c_int) :: stat
        character(kind=c_char), pointer :: chars(:)

        call self%destroy()
        if (nx < 1 .or. ny < 1) then
            call fatal_error(error, "veslide:fftw:init: grid size must be positive"); return
        end if
        flag = FFTW_MEASURE
        if (present(planner)) flag = fft_planner_flag(planner)
        nthreads_ = 1
        if (present(nthreads)) nthreads_ = max(1, nthreads)
        if (nthreads_ > 1 .and. .not. threads_ready) then
            if (fftw_init_threads() == 0) then
                call fatal_error(error, "veslide:fftw:init: fftw_init_threads failed"); return
            end if
            threads_ready = .true.
        end if
        isolated_ = .false.; if (present(isolated)) isolated_ = isolated
        if (isolated_) then
            flag = FFTW_ESTIMATE; nthreads_ = 1
        end if
        if (threads_ready) call fftw_plan_with_nthreads(int(nthreads_, c_int))

        self%nx = nx; self%ny = ny
        self%p_x = fftw_alloc_real(int(nx, c_size_t)*int(ny, c_size_t))
        self%p_k = fftw_alloc_complex(int(nx/2 + 1, c_size_t)*int(ny, c_size_t))
        if (.not. (c_associated(self%p_x) .and. c_associated(self%p_k))) then
            call fatal_error(error, "veslide:fftw:init: cannot allocate FFT buffers"); return
        end if
        call c_f_pointer(self%p_x, self%x, [nx, ny])
        call c_f_pointer(self%p_k, self%k, [nx/2 + 1, ny])
        ! FFTW is row-major: dimensions are passed reversed
        if (isolated_) then
            saved = fftw_export_wisdom_to_string()
            call fftw_forget_wisdom()
        end if
        self%plan_r2c = fftw_plan_dft_r2c_2d(int(ny, c_int), int(nx, c_int), self%x, self%k, flag)
        self%plan_c2r = fftw_plan_dft_c2r_2d(int(ny, c_int), int(nx, c_int), self%k, self%x, flag)
        if (isolated_) then
            call fftw_forget_wisdom()
            if (c_associated(saved)) then
                call c_f_pointer(saved, chars, [c_strlen(saved) + 1])
                stat = fftw_import_wisdom_from_string(chars)
                call c_free(saved)
            end if
        end if
        if (.not. (c_associated(self%plan_r2c) .and. c_associated(self%plan_c2r))) then
            call fatal_error(error, "veslide:fftw:init: FFTW returned a null plan"); return
        end if
        self%x = 0.0_c_double
        self%k = (0.0_c_double, 0.0_c_double)
    end subroutine fft_init

    !> x -> k (unnormalised forward transform, exp(-i q.x))
    subroutine fft_forward(self)
        class(fft2d_t), intent(inout) :: self
        call fftw_execute_dft_r2c(self%plan_r2c, self%x, self%k)
    end subroutine fft_forward

    !> k -> x, divided by nx*ny (the input k is destroyed, as FFTW's c2r does)
    subroutine fft_backward(self)
        class(fft2d_t), intent(inout) :: self
        call fftw_execute_dft_c2r(self%plan_c2r, self%k, self%x)
        self%x = self%x/real(self%nx*self%ny, c_double)
    end subroutine fft_backward

    !> k -> x without the 1/(nx*ny) factor (for callers that fold it into a multiplier)
    subroutine fft_backward_unscaled(self)
        class(fft2d_t), intent(inout) :: self
        call fftw_execute_dft_c2r(self%plan_c2r, self%k, self%x)
    end subroutine fft_backward_unscaled

    !> Free plans and buffers
    subroutine fft_destroy(self)
        class(fft2d_t), intent(inout) :: self
        if (c_associated(self%plan_r2c)) call fftw_destroy_plan(self%plan_r2c)
        if (c_associated(self%plan_c2r)) call fftw_destroy_plan(self%plan_c2r)
        if (c_associated(self%p_x)) call fftw_free(self%p_x)
        if (c_associated(self%p_k)) call fftw_free(self%p_k)
        self%plan_r2c = c_null_ptr; self%plan_c2r = c_null_ptr
        self%p_x = c_null_ptr; self%p_k = c_null_ptr
        nullify (self%x, self%k)
        self%nx = 0; self%ny = 0
    end subroutine fft_destroy

    subroutine fft_finalize(self)
        type(fft2d_t), intent(inout) :: self
        call self%destroy()
    end subroutine fft_finalize

end module veslide_fftw
