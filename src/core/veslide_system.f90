!> The operating system, through a small C file (veslide_posix.c): the kind of a path, an
!> advisory lock, SIGXFSZ made an ordinary write error, the memory a process may use, and
!> OpenMP's passive wait chosen for a program whose user did not choose (prefer_passive_wait),
!> and the number of OpenMP threads a run asks for (use_threads)
module veslide_system
    use, intrinsic :: iso_c_binding, only: c_int, c_long_long, c_char, c_null_char
    !$ use omp_lib, only: omp_set_num_threads
    use veslide_kinds, only: i8
    use veslide_strings, only: c_text
    implicit none
    private
    public :: path_kind, PATH_MISSING, PATH_REGULAR, PATH_DIRECTORY, PATH_OTHER
    public :: lock_file, unlock_file, LOCK_BUSY, ignore_file_size_signal, last_system_error, missing_reason
    public :: catch_termination, defer_termination, allow_termination
    public :: available_memory_bytes, peak_memory_bytes, resident_memory_bytes, exit_now, prefer_passive_wait
    public :: use_threads, rename_file, link_file, remove_file, process_id

    integer, parameter :: PATH_MISSING = -1, PATH_REGULAR = 0, PATH_DIRECTORY = 1, PATH_OTHER = 2
    !> lock_file's result when another process holds the lock
    integer, parameter :: LOCK_BUSY = -2

    interface
        integer(c_int) function c_path_kind(path) bind(c, name='veslide_path_kind')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
        end function c_path_kind
        integer(c_int) function c_rename(old, new) bind(c, name='rename')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: old(*), new(*)
        end function c_rename
        integer(c_int) function c_link(old, new) bind(c, name='link')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: old(*), new(*)
        end function c_link
        integer(c_int) function c_unlink(path) bind(c, name='unlink')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
        end function c_unlink
        integer(c_int) function c_getpid() bind(c, name='getpid')
            import :: c_int
        end function c_getpid
        subroutine c_last_error(buf, n) bind(c, name='veslide_last_error')
            import :: c_char, c_int
            character(kind=c_char), intent(out) :: buf(*)
            integer(c_int), value :: n
        end subroutine c_last_error
        integer(c_int) function c_lock(path) bind(c, name='veslide_lock')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: path(*)
        end function c_lock
        subroutine c_unlock(fd) bind(c, name='veslide_unlock')
            import :: c_int
            integer(c_int), value :: fd
        end subroutine c_unlock
        subroutine ignore_file_size_signal() bind(c, name='veslide_ignore_sigxfsz')
        end subroutine ignore_file_size_signal
        !> Termination signals (SIGTERM, SIGINT, SIGHUP) held off inside defer_termination ..
        !> allow_termination (first thing in a program; without it those two do nothing)
        subroutine catch_termination() bind(c, name='veslide_catch_termination')
        end subroutine catch_termination
        !> From here a termination signal waits for allow_termination (a file being written)
        subroutine defer_termination() bind(c, name='veslide_defer_termination')
        end subroutine defer_termination
        !> A termination signal that came since defer_termination ends the process now
        subroutine allow_termination() bind(c, name='veslide_allow_termination')
        end subroutine allow_termination
        !> Unless OMP_WAIT_POLICY is set, run this program again with it 'passive' (first thing
        !> in a program: before any OpenMP region; returns when nothing was done)
        subroutine prefer_passive_wait() bind(c, name='veslide_prefer_passive_wait')
        end subroutine prefer_passive_wait
        subroutine c_exit(status) bind(c, name='veslide_exit')
            import :: c_int
            integer(c_int), value :: status
        end subroutine c_exit
        integer(c_long_long) function c_available() bind(c, name='veslide_available_bytes')
            import :: c_long_long
        end function c_available
        integer(c_long_long) function c_peak() bind(c, name='veslide_peak_rss_bytes')
            import :: c_long_long
        end function c_peak
        integer(c_long_long) function c_rss() bind(c, name='veslide_rss_bytes')
            import :: c_long_long
        end function c_rss
    end interface

contains

    !> End the process with `status` after flushing Fortran's units, without running the exit
    !> handlers of libraries (a controlled exit after an I/O failure, whatever state HDF5 is in)
    subroutine exit_now(status)
        use, intrinsic :: iso_fortran_env, only: output_unit, error_unit
        integer, intent(in) :: status
        flush (output_unit); flush (error_unit)
        call c_exit(int(status, c_int))
    end subroutine exit_now

    !> Run the OpenMP regions that follow on `n` threads; n <= 0 leaves the number as it is
    !> (OMP_NUM_THREADS, else one per core). Results do not depend on it (README: Reproducible).
    subroutine use_threads(n)
        integer, intent(in) :: n
        !$ if (n > 0) call omp_set_num_threads(n)
    end subroutine use_threads

    !> POSIX rename(2): replace `new` by `old` in one step; .true. when done
    logical function rename_file(old, new) result(ok)
        character(len=*), intent(in) :: old, new
        ok = c_rename(old//c_null_char, new//c_null_char) == 0
    end function rename_file

    !> POSIX link(2): `new` names the file `old` names, never replacing an existing `new`
    logical function link_file(old, new) result(ok)
        character(len=*), intent(in) :: old, new
        ok = c_link(old//c_null_char, new//c_null_char) == 0
    end function link_file

    !> POSIX unlink(2), whose failure (a missing file) the callers do not need
    subroutine remove_file(path)
        character(len=*), intent(in) :: path
        integer(c_int) :: stat
        stat = c_unlink(path//c_null_char)
    end subroutine remove_file

    !> The process id (POSIX getpid), for names unique to this run
    integer function process_id() result(pid)
        pid = int(c_getpid())
    end function process_id

    !> PATH_MISSING, PATH_REGULAR, PATH_DIRECTORY or PATH_OTHER (FIFO, device, socket)
    integer function path_kind(path) result(kind)
        character(len=*), intent(in) :: path
        kind = int(c_path_kind(path//c_null_char))
    end function path_kind

    !> An exclusive advisory lock on `path`, held until unlock_file or the end of the process:
    !> a descriptor >= 0, LOCK_BUSY when another process holds it, -1 on another failure
    integer function lock_file(path) result(fd)
        character(len=*), intent(in) :: path
        fd = int(c_lock(path//c_null_char))
    end function lock_file

    !> The system's own words for the last failure of path_kind or lock_file ('File name too
    !> long', 'Permission denied', ...); '' when it did not fail
    function last_system_error() result(reason)
        character(len=:), allocatable :: reason
        character(kind=c_char) :: buf(256)
        call c_last_error(buf, int(size(buf), c_int))
        reason = c_text(buf)
    end function last_system_error

    !> Why `path` cannot be opened for reading, in the system's words ('No such file or
    !> directory', 'File name too long', 'Permission denied' for a directory on the way); ''
    !> when it exists
    function missing_reason(path) result(reason)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: reason
        reason = ''
        if (path_kind(path) /= PATH_MISSING) return
        reason = last_system_error()
        if (len(reason) == 0) reason = 'no such file'
    end function missing_reason

    subroutine unlock_file(fd)
        integer, intent(in) :: fd
        call c_unlock(int(fd, c_int))
    end subroutine unlock_file

    !> Bytes the process may still allocate (machine, rlimits, cgroup); -1 when unknown
    integer(i8) function available_memory_bytes() result(b)
        b = int(c_available(), i8)
    end function available_memory_bytes

    !> Peak resident set size of the process so far [bytes]
    integer(i8) function peak_memory_bytes() result(b)
        b = int(c_peak(), i8)
    end function peak_memory_bytes

    !> Resident set size now [bytes]
    integer(i8) function resident_memory_bytes() result(b)
        b = int(c_rss(), i8)
    end function resident_memory_bytes

end module veslide_system
