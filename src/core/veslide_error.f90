!> The one error type of veslide, shared by library, application and tests.
!>
!> Fallible procedures end with `type(error_t), allocatable, intent(out) :: error`; callers test
!> `allocated(error)` and return. Only the application prints a message and sets the exit status,
!> which follows from the error's category (`exit_status`): the input asks for what cannot be
!> done (1), reading or writing a file failed (3), the numbers broke down (4); a solve that ran
!> but did not converge is not an error (the programs exit with 2).
module veslide_error
    implicit none
    private
    public :: error_t, fatal_error, io_error, add_context, exit_status
    public :: ERROR_INPUT, ERROR_IO, ERROR_NUMERICAL

    !> What went wrong: the input (the default), a file's reading or writing, the numbers
    integer, parameter :: ERROR_INPUT = 1, ERROR_IO = 2, ERROR_NUMERICAL = 3

    !> An error raised by a fallible procedure; the message names module, procedure and object
    type :: error_t
        character(len=:), allocatable :: message   !! human-readable one-line description
        integer :: category = ERROR_INPUT          !! ERROR_*
    end type error_t

contains

    !> Allocate `error` and store `message` in it
    pure subroutine fatal_error(error, message, category)
        !> error to create
        type(error_t), allocatable, intent(out) :: error
        !> one-line description
        character(len=*), intent(in) :: message
        !> ERROR_* (default ERROR_INPUT)
        integer, intent(in), optional :: category
        allocate (error)
        error%message = message
        if (present(category)) error%category = category
    end subroutine fatal_error

    !> A file could not be read or written (ERROR_IO): fatal_error of that category
    pure subroutine io_error(error, message)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in) :: message
        call fatal_error(error, message, ERROR_IO)
    end subroutine io_error

    !> The exit status of a program that stops on `error`: 1 input, 3 I/O, 4 numerical
    pure integer function exit_status(error) result(status)
        type(error_t), intent(in) :: error
        select case (error%category)
        case (ERROR_IO)
            status = 3
        case (ERROR_NUMERICAL)
            status = 4
        case default
            status = 1
        end select
    end function exit_status

    !> Prefix the message of an allocated error with `context` (the input that caused it, e.g.
    !> "veslide: run.nml: &material: "); does nothing when no error is allocated
    pure subroutine add_context(error, context)
        !> error to annotate
        type(error_t), allocatable, intent(inout) :: error
        !> text put in front of the message
        character(len=*), intent(in) :: context
        if (allocated(error)) error%message = context//error%message
    end subroutine add_context

end module veslide_error
