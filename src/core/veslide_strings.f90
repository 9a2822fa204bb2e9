!> Text helpers for messages: numbers as short strings, lower case
module veslide_strings
    use veslide_kinds, only: dp, i8
    implicit none
    private
    public :: str, lower

    !> A number as the shortest readable text: integers with i0, reals with g0.6
    interface str
        module procedure str_int, str_int8, str_real
    end interface str

contains

    pure function str_int(i) result(s)
        integer, intent(in) :: i
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') i
        s = trim(buf)
    end function str_int

    pure function str_int8(i) result(s)
        integer(i8), intent(in) :: i
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') i
        s = trim(buf)
    end function str_int8

    pure function str_real(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(g0.6)') x
        s = trim(adjustl(buf))
    end function str_real

    !> `s` with A-Z turned to a-z
    pure function lower(s) result(t)
        character(len=*), intent(in) :: s
        character(len=len(s)) :: t
        integer :: k
        t = s
        do k = 1, len(s)
            if (s(k:k) >= 'A' .and. s(k:k) <= 'Z') t(k:k) = achar(iachar(s(k:k)) + 32)
        end do
    end function lower

end module veslide_strings
