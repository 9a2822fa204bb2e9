!> The one error type of veslide, shared by library, application and tests.
!>
!> Fallible procedures end with `type(error_t), allocatable, intent(out) :: error`; callers test
!> `allocated(error)` and return. Only the application prints a message and sets the exit status.
module veslide_error
    implicit none
    private
    public :: error_t, fatal_error, add_context

    !> An error raised by a fallible procedure; the message names module, procedure and object
    type :: error_t
        character(len=:), allocatable :: message   !! human-readable one-line description
    end type error_t

contains

    !> Allocate `error` and store `message` in it
    pure subroutine fatal_error(error, message)
        !> error to create
        type(error_t), allocatable, intent(out) :: error
        !> one-line description
        character(len=*), intent(in) :: message
        allocate (error)
        error%message = message
    end subroutine fatal_error

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
