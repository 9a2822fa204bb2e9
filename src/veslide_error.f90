!> The one error type of veslide, shared by library, application and tests
module veslide_error
    implicit none
    private
    public :: error_t, fatal_error

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

end module veslide_error
