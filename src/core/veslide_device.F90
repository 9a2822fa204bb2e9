!> The device seam: a GPU (or the emulated device) as the solvers see it, and nothing when the
!> library is built without one (then `device_enabled` is false, `device_count` is 0 and every
!> other procedure answers with an error), as `veslide_collective` is without MPI.
!>
!> Built with -DVESLIDE_CUDA (gpu/build.sh) the procedures call the C functions of
!> src/core/veslide_device.cu: the CUDA runtime on a GPU, or host memory on the emulated device
!> (gpu/build.sh --emulate, which runs the device path where no GPU is: tests and CI).
!> Device memory is `type(c_ptr)`; what lives there is only ever touched by the passes
!> (the veslide_*_passes.cu files) and by the copies here. A failed device call is kept (sticky) and
!> turned into an `error_t` by `device_check`, which the solvers call between iterations.
module veslide_device
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int, c_size_t, c_double, c_char, c_null_char, &
                                           c_associated
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: c_text
    implicit none
    private
    public :: device_enabled, device_emulated, device_count, device_select, device_info_t, device_info, &
              device_alloc, device_free, device_upload, device_download, device_copy, device_zero, &
              device_sync, device_check, device_failed, device_bytes_in_use, device_peak_bytes, &
              device_reset_peak, device_clock, device_memory, device_profile, device_has_room, device_moved_bytes

    !> Was the library built with a device (-DVESLIDE_CUDA)?
#ifdef VESLIDE_CUDA
    logical, parameter :: device_enabled = .true.
#else
    logical, parameter :: device_enabled = .false.
#endif

    !> What a device is (the provenance of a result computed on it)
    type :: device_info_t
        character(len=:), allocatable :: name     !! e.g. 'NVIDIA H200'
        integer :: ordinal = -1                   !! CUDA device number
        real(dp) :: memory_bytes = 0.0_dp         !! its memory [bytes]
        integer :: driver_version = 0             !! CUDA driver API version, 1000 major + 10 minor
        integer :: runtime_version = 0            !! CUDA runtime version, likewise
        integer :: compute_capability = 0         !! 10 major + minor (90: Hopper)
        logical :: emulated = .false.             !! the emulated device (host memory, no GPU)
    end type device_info_t

#ifdef VESLIDE_CUDA
    interface
        integer(c_int) function c_emulated() bind(c, name='veslide_device_emulated')
            import :: c_int
        end function c_emulated
        integer(c_int) function c_count() bind(c, name='veslide_device_count')
            import :: c_int
        end function c_count
        integer(c_int) function c_select(ordinal) bind(c, name='veslide_device_select')
            import :: c_int
            integer(c_int), value :: ordinal
        end function c_select
        integer(c_int) function c_properties(ordinal, name, len, total, driver, runtime, ccmaj, ccmin) &
            bind(c, name='veslide_device_properties')
            import :: c_int, c_char, c_double
            integer(c_int), value :: ordinal, len
            character(kind=c_char) :: name(*)
            real(c_double), intent(out) :: total
            integer(c_int), intent(out) :: driver, runtime, ccmaj, ccmin
        end function c_properties
        integer(c_int) function c_memory(free, total) bind(c, name='veslide_device_memory')
            import :: c_int, c_double
            real(c_double), intent(out) :: free, total
        end function c_memory
        integer(c_int) function c_alloc(p, bytes) bind(c, name='veslide_device_alloc')
            import :: c_int, c_ptr, c_size_t
            type(c_ptr), intent(out) :: p
            integer(c_size_t), value :: bytes
        end function c_alloc
        integer(c_int) function c_free(p) bind(c, name='veslide_device_free')
            import :: c_int, c_ptr
            type(c_ptr), value :: p
        end function c_free
        integer(c_int) function c_upload(dest, src, bytes) bind(c, name='veslide_device_upload')
            import :: c_int, c_ptr, c_size_t
            type(c_ptr), value :: dest
            type(*), intent(in) :: src(*)
            integer(c_size_t), value :: bytes
        end function c_upload
        integer(c_int) function c_download(dest, src, bytes) bind(c, name='veslide_device_download')
            import :: c_int, c_ptr, c_size_t
            type(*), intent(inout) :: dest(*)
            type(c_ptr), value :: src
            integer(c_size_t), value :: bytes
        end function c_download
        integer(c_int) function c_copy(dest, src, bytes) bind(c, name='veslide_device_copy')
            import :: c_int, c_ptr, c_size_t
            type(c_ptr), value :: dest, src
            integer(c_size_t), value :: bytes
        end function c_copy
        integer(c_int) function c_zero(dest, bytes) bind(c, name='veslide_device_zero')
            import :: c_int, c_ptr, c_size_t
            type(c_ptr), value :: dest
            integer(c_size_t), value :: bytes
        end function c_zero
        integer(c_int) function c_sync() bind(c, name='veslide_device_sync')
            import :: c_int
        end function c_sync
        integer(c_int) function c_failed() bind(c, name='veslide_device_failed')
            import :: c_int
        end function c_failed
        subroutine c_take_error(msg, len) bind(c, name='veslide_device_take_error')
            import :: c_char, c_int
            character(kind=c_char) :: msg(*)
            integer(c_int), value :: len
        end subroutine c_take_error
        real(c_double) function c_bytes_in_use() bind(c, name='veslide_device_bytes_in_use')
            import :: c_double
        end function c_bytes_in_use
        real(c_double) function c_peak_bytes() bind(c, name='veslide_device_peak_bytes')
            import :: c_double
        end function c_peak_bytes
        subroutine c_reset_peak() bind(c, name='veslide_device_reset_peak')
        end subroutine c_reset_peak
        real(c_double) function c_moved(up) bind(c, name='veslide_device_moved_bytes')
            import :: c_double, c_int
            integer(c_int), value :: up
        end function c_moved
        real(c_double) function c_clock() bind(c, name='veslide_device_clock')
            import :: c_double
        end function c_clock
        subroutine c_profile() bind(c, name='veslide_device_profile')
        end subroutine c_profile
    end interface
#endif

    !> The ordinal selected by device_select (-1: none yet; the runtime's default, 0, is used)
    integer, save :: selected = -1

contains

    !> Is this build's device the emulated one (host memory, no GPU)?
    logical function device_emulated() result(yes)
#ifdef VESLIDE_CUDA
        yes = c_emulated() /= 0
#else
        yes = .false.
#endif
    end function device_emulated

    !> Devices visible to this process (0 without device support, or when none is visible)
    integer function device_count() result(n)
#ifdef VESLIDE_CUDA
        n = c_count()
#else
        n = 0
#endif
    end function device_count

    !> Use device `ordinal` (0-based) for what follows (an MPI rank takes rank modulo the count)
    subroutine device_select(ordinal, error)
        integer, intent(in) :: ordinal
        type(error_t), allocatable, intent(out) :: error
#ifdef VESLIDE_CUDA
        if (c_select(int(ordinal, c_int)) /= 0) then
            call device_check(error, "veslide:device:select"); return
        end if
        selected = ordinal
#else
        call no_device(error, "veslide:device:select")
#endif
    end subroutine device_select

    !> The device in use: name, memory, driver and runtime versions
    subroutine device_info(info, error)
        type(device_info_t), intent(out) :: info
        type(error_t), allocatable, intent(out) :: error
#ifdef VESLIDE_CUDA
        character(kind=c_char) :: name(256)
        real(c_double) :: total
        integer(c_int) :: driver, runtime, ccmaj, ccmin, ordinal
        ordinal = int(max(selected, 0), c_int)
        if (c_properties(ordinal, name, int(size(name), c_int), total, driver, runtime, ccmaj, ccmin) /= 0) then
            call device_check(error, "veslide:device:info"); return
        end if
        info%name = c_text(name)
        info%ordinal = ordinal
        info%memory_bytes = total
        info%driver_version = driver; info%runtime_version = runtime
        info%compute_capability = 10*ccmaj + ccmin
        info%emulated = device_emulated()
#else
        call no_device(error, "veslide:device:info")
        info%ordinal = -1
#endif
    end subroutine device_info

    !> Free and total memory of the device in use [bytes] (-1: unknown, the emulated device)
    subroutine device_memory(free_bytes, total_bytes, error)
        real(dp), intent(out) :: free_bytes, total_bytes
        type(error_t), allocatable, intent(out) :: error
#ifdef VESLIDE_CUDA
        if (c_memory(free_bytes, total_bytes) /= 0) call device_check(error, "veslide:device:memory")
#else
        free_bytes = -1; total_bytes = -1
        call no_device(error, "veslide:device:memory")
#endif
    end subroutine device_memory

    !> Has the device room for `bytes` more beside what it holds, with the allowance veslide_memory
    !> keeps for the runtime and the row partials (64 MiB)? Yes where its free memory is unknown
    !> (the emulated device); no with VESLIDE_DEVICE_LEAN=1 in the environment (a solver's lean
    !> layout asked for: veslide_solver_pdr)
    logical function device_has_room(bytes) result(yes)
        real(dp), intent(in) :: bytes
        real(dp) :: free_b, total_b
        type(error_t), allocatable :: error
        character(len=8) :: lean
        integer :: l, st
        yes = .false.
        call get_environment_variable('VESLIDE_DEVICE_LEAN', lean, l, st)
        if (st == 0 .and. lean == '1') return
        call device_memory(free_b, total_b, error)
        yes = .true.
        if (allocated(error)) return
        if (free_b >= 0.0_dp) yes = free_b >= bytes + 64.0_dp*1024*1024
    end function device_has_room

    !> `bytes` of device memory at `p` (the failure, if any, is kept for device_check)
    subroutine device_alloc(p, bytes)
        type(c_ptr), intent(out) :: p
        integer(i8), intent(in) :: bytes
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        stat = c_alloc(p, int(max(bytes, 1_i8), c_size_t))
#else
        p = c_null_ptr
#endif
    end subroutine device_alloc

    !> Device memory back (a null pointer is ignored); `p` is nulled
    subroutine device_free(p)
        type(c_ptr), intent(inout) :: p
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        if (c_associated(p)) stat = c_free(p)
#endif
        p = c_null_ptr
    end subroutine device_free

    !> `bytes` bytes from the host array `src` (contiguous) to the device at `dest`
    subroutine device_upload(dest, src, bytes)
        type(c_ptr), intent(in) :: dest
        type(*), intent(in) :: src(*)
        integer(i8), intent(in) :: bytes
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        stat = c_upload(dest, src, int(bytes, c_size_t))
#else
#endif
    end subroutine device_upload

    !> `bytes` bytes from the device at `src` to the host array `dest` (contiguous)
    subroutine device_download(dest, src, bytes)
        type(*), intent(inout) :: dest(*)
        type(c_ptr), intent(in) :: src
        integer(i8), intent(in) :: bytes
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        stat = c_download(dest, src, int(bytes, c_size_t))
#else
#endif
    end subroutine device_download

    !> `bytes` bytes from device memory `src` to device memory `dest`
    subroutine device_copy(dest, src, bytes)
        type(c_ptr), intent(in) :: dest, src
        integer(i8), intent(in) :: bytes
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        stat = c_copy(dest, src, int(bytes, c_size_t))
#else
#endif
    end subroutine device_copy

    !> `bytes` bytes of device memory at `dest` set to zero
    subroutine device_zero(dest, bytes)
        type(c_ptr), intent(in) :: dest
        integer(i8), intent(in) :: bytes
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        stat = c_zero(dest, int(bytes, c_size_t))
#else
#endif
    end subroutine device_zero

    !> Wait for the device to finish what it was given
    subroutine device_sync()
#ifdef VESLIDE_CUDA
        integer(c_int) :: stat
        stat = c_sync()
#endif
    end subroutine device_sync

    !> Has a device call failed since the last device_check?
    logical function device_failed() result(yes)
#ifdef VESLIDE_CUDA
        yes = c_failed() /= 0
#else
        yes = .false.
#endif
    end function device_failed

    !> The first device failure since the last check as an error of `where` (none: no error)
    subroutine device_check(error, where)
        type(error_t), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: where
#ifdef VESLIDE_CUDA
        character(kind=c_char) :: msg(512)
        if (c_failed() == 0) return
        call c_take_error(msg, int(size(msg), c_int))
        if (.not. allocated(error)) call fatal_error(error, where//": "//c_text(msg))
#else
#endif
    end subroutine device_check

    !> Bytes of device memory veslide holds now (cuFFT's work areas included)
    real(dp) function device_bytes_in_use() result(b)
#ifdef VESLIDE_CUDA
        b = c_bytes_in_use()
#else
        b = 0.0_dp
#endif
    end function device_bytes_in_use

    !> The most device memory veslide held at once since the last reset [bytes]
    real(dp) function device_peak_bytes() result(b)
#ifdef VESLIDE_CUDA
        b = c_peak_bytes()
#else
        b = 0.0_dp
#endif
    end function device_peak_bytes

    !> Bytes moved to the device (`up`) or from it by uploads and downloads of arrays since the
    !> program began (the row partials not counted)
    real(dp) function device_moved_bytes(up) result(b)
        logical, intent(in) :: up
#ifdef VESLIDE_CUDA
        b = c_moved(merge(1_c_int, 0_c_int, up))
#else
        b = 0.0_dp
        if (up) b = 0.0_dp
#endif
    end function device_moved_bytes

    !> Start a new peak from what is held now
    subroutine device_reset_peak()
#ifdef VESLIDE_CUDA
        call c_reset_peak()
#endif
    end subroutine device_reset_peak

    !> Seconds since an arbitrary origin, once the device has finished its work (timing)
    real(dp) function device_clock() result(t)
#ifdef VESLIDE_CUDA
        t = c_clock()
#else
        t = 0.0_dp
#endif
    end function device_clock

    !> With VESLIDE_DEVICE_PROFILE=1: the time of every pass since the last call, as a table on
    !> standard output (a benchmark's; the library itself prints nothing otherwise)
    subroutine device_profile()
#ifdef VESLIDE_CUDA
        flush (6)
        call c_profile()
#endif
    end subroutine device_profile

#ifndef VESLIDE_CUDA
    subroutine no_device(error, where)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in) :: where
        call fatal_error(error, where//": this build of veslide has no device support (build it with"// &
                         " gpu/build.sh to run on a GPU)")
    end subroutine no_device
#endif

end module veslide_device
