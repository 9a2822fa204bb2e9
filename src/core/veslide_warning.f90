!> Validity as data: the measures of a case's validity (`measure_t`: a number, its units and the
!> threshold past which it warns) and the warnings (`warning_t`): what a run found questionable
!> about its input or its result, kept with the result (the output file's /warnings, a study
!> case's /cases/NNNNNN/warnings), printed on stderr by the programs (never silenced by --quiet)
!> and re-raised by the Python package.
!>
!> A warning has a stable `code` (hyphenated; scripts filter on it; docs/validity.md lists every
!> code), the number it measured and the threshold that number crossed (both 0 when the warning
!> is about a choice, not a number: an input that changes nothing), one line of text saying what
!> and what to do, and its source: 'input' (the namelist and the files it names, found before the
!> solve) or 'validity' (the solved case's validity measures, veslide_validity).
module veslide_warning
    use veslide_kinds, only: dp
    implicit none
    private
    public :: warning_t, add_warning, warning_line, count_source, measure_t, add_measure
    public :: WARNS_NEVER, WARNS_ABOVE, WARNS_BELOW

    type :: warning_t
        character(len=:), allocatable :: code        !! stable name, e.g. 'contact-resolution'
        character(len=:), allocatable :: text        !! one line: what was found and what to do
        real(dp) :: value = 0.0_dp                   !! the number measured (0: none)
        real(dp) :: threshold = 0.0_dp               !! the threshold it crossed (0: none)
        character(len=:), allocatable :: source      !! 'input' or 'validity'
    end type warning_t

    !> When a measure warns: never (a number for the reader), above its threshold, below it
    integer, parameter :: WARNS_NEVER = 0, WARNS_ABOVE = 1, WARNS_BELOW = 2

    !> One validity measure of a case (veslide_validity defines each and its threshold)
    type :: measure_t
        character(len=:), allocatable :: name        !! HDF5 name under /validity, /summary column
        character(len=:), allocatable :: units       !! '-' for none
        real(dp) :: value = 0.0_dp
        real(dp) :: threshold = 0.0_dp               !! where it starts to warn
        integer :: warns = WARNS_NEVER               !! WARNS_*
        logical :: is_integer = .false.              !! a count (int64 in the file)
    end type measure_t

contains

    !> Append a measure to `list` (allocated empty first when it is not)
    pure subroutine add_measure(list, name, value, units, warns, threshold, is_integer)
        type(measure_t), allocatable, intent(inout) :: list(:)
        character(len=*), intent(in) :: name, units
        real(dp), intent(in) :: value
        integer, intent(in), optional :: warns
        real(dp), intent(in), optional :: threshold
        logical, intent(in), optional :: is_integer
        type(measure_t) :: m
        m%name = name; m%units = units; m%value = value
        if (present(warns)) m%warns = warns
        if (present(threshold)) m%threshold = threshold
        if (present(is_integer)) m%is_integer = is_integer
        if (.not. allocated(list)) allocate (list(0))
        list = [list, m]
    end subroutine add_measure

    !> Append a warning to `list` (allocated empty first when it is not)
    pure subroutine add_warning(list, code, text, source, value, threshold)
        type(warning_t), allocatable, intent(inout) :: list(:)
        character(len=*), intent(in) :: code, text, source
        real(dp), intent(in), optional :: value, threshold
        type(warning_t) :: w
        w%code = code; w%text = text; w%source = source
        if (present(value)) w%value = value
        if (present(threshold)) w%threshold = threshold
        if (.not. allocated(list)) allocate (list(0))
        list = [list, w]
    end subroutine add_warning

    !> The line a program prints for `w`: "veslide: WHERE: warning [code]: text"
    pure function warning_line(w, where) result(line)
        type(warning_t), intent(in) :: w
        character(len=*), intent(in) :: where      !! the input's path, or 'FILE: case N'
        character(len=:), allocatable :: line
        line = "veslide: "//where//": warning ["//w%code//"]: "//w%text
    end function warning_line

    !> How many warnings of `list` come from `source`
    pure integer function count_source(list, source) result(n)
        type(warning_t), intent(in) :: list(:)
        character(len=*), intent(in) :: source
        integer :: k
        n = 0
        do k = 1, size(list)
            if (list(k)%source == source) n = n + 1
        end do
    end function count_source

end module veslide_warning
