!> Text helpers: numbers as short strings for messages, lower case, the index of a name in a
!> table of names (the library's enumerations), and C strings (null-terminated, from C libraries)
module veslide_strings
    use, intrinsic :: iso_c_binding, only: c_ptr, c_char, c_size_t, c_associated, c_f_pointer, c_null_char
    use veslide_kinds, only: dp, i8
    implicit none
    private
    public :: str, sig, lower, name_index, c_strlen, c_string, c_text

    interface
        !> strlen(3) of a null-terminated C string
        integer(c_size_t) function c_strlen(s) bind(c, name='strlen')
            import :: c_ptr, c_size_t
            type(c_ptr), value :: s
        end function c_strlen
    end interface

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

    !> `x` to `digits` significant digits (default 3), as a reader writes it: '0.025', '2.4',
    !> '150', '2.0e+03', '9.8e+06', '1.0e-05' (fixed notation from 1e-3 to 1e4, trailing zeros
    !> dropped; else the exponent form with `digits` digits)
    pure function sig(x, digits) result(s)
        real(dp), intent(in) :: x
        integer, intent(in), optional :: digits
        character(len=:), allocatable :: s
        character(len=48) :: buf, fmt
        integer :: d, decimals, e
        d = 3; if (present(digits)) d = max(1, min(digits, 15))
        if (x /= x) then
            s = 'NaN'; return
        else if (abs(x) > huge(x)) then
            s = merge('-Inf', ' Inf', x < 0.0_dp); s = trim(adjustl(s)); return
        else if (x == 0.0_dp) then
            s = '0'; return
        end if
        if (abs(x) >= 1.0e-3_dp .and. abs(x) < 1.0e4_dp) then
            e = floor(log10(abs(x)))
            decimals = max(0, d - 1 - e)
            write (fmt, '(a,i0,a)') '(f0.', decimals, ')'
            write (buf, fmt) x
            s = trim(adjustl(buf))
            if (index(s, '.') > 0) then
                do while (s(len(s):len(s)) == '0')
                    s = s(:len(s) - 1)
                end do
                if (s(len(s):len(s)) == '.') s = s(:len(s) - 1)
            end if
            if (s(1:1) == '.') s = '0'//s
            if (len(s) > 1) then
                if (s(1:2) == '-.') s = '-0'//s(2:)
            end if
        else
            write (fmt, '(a,i0,a,i0,a)') '(es', d + 8, '.', d - 1, 'e2)'
            write (buf, fmt) x
            s = trim(adjustl(buf))
            s = lower(s)
        end if
    end function sig

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

    !> Position of `name` in `names` (trailing blanks ignored); 0 when absent
    pure integer function name_index(name, names) result(id)
        character(len=*), intent(in) :: name, names(:)
        integer :: k
        id = 0
        do k = 1, size(names)
            if (trim(name) == trim(names(k))) then
                id = k; return
            end if
        end do
    end function name_index

    !> A copy of the null-terminated C string at `ptr` ('' for a null pointer)
    function c_string(ptr) result(s)
        type(c_ptr), intent(in) :: ptr
        character(len=:), allocatable :: s
        character(kind=c_char), pointer :: chars(:)
        integer :: n, k
        if (.not. c_associated(ptr)) then
            s = ''; return
        end if
        n = int(c_strlen(ptr))
        call c_f_pointer(ptr, chars, [n])
        allocate (character(len=n) :: s)
        do k = 1, n
            s(k:k) = chars(k)
        end do
    end function c_string

    !> The text a C function wrote into the character buffer `s`, up to its null (or the whole
    !> buffer when it has none)
    pure function c_text(s) result(t)
        character(kind=c_char), intent(in) :: s(:)
        character(len=:), allocatable :: t
        integer :: n
        n = 0
        do while (n < size(s))
            if (s(n + 1) == c_null_char) exit
            n = n + 1
        end do
        allocate (character(len=n) :: t)
        t = transfer(s(1:n), t)
    end function c_text

end module veslide_strings
