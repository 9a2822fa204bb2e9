!> What every namelist group shares: the scan of the input file into its groups (known names, no
!> duplicates, nothing outside groups), the read of one group from its own text with a diagnosis
!> that names the offending variable, the sentinel of unset list entries, and refusals that name
!> the file, the group, the variable, the value and the allowed range.
module veslide_config_common
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: name_index, lower, str
    implicit none
    private
    public :: group_text_t, scan_namelist, get_group, diagnose_read, try_interface, read_failed, split_lines
    public :: range_error, require, choices_text, is_one_of, finite_in, max_list, max_terms, max_text
    public :: unset_real, is_unset, list_length, check_list, check_text_length, assigned_names

    !> Longest list a &sweep array may hold
    integer, parameter :: max_list = 64
    !> Most Prony terms (and shift-table points) &material takes: a master curve over 40 decades at
    !> 6 terms a decade, the most candidates `veslide.material.fit_prony` offers. The terms cost
    !> only when a kernel is built (once per speed and temperature; the solve does not see them):
    !> sliding along a grid axis the compliance is evaluated once per column, at an oblique
    !> direction once per mode, where a long series sums one by one only the terms near the
    !> mode's frequency (material_compliance): either way 200 terms add less than 1 % to a
    !> 512^2 case with 20 (docs/benchmarks.md)
    integer, parameter :: max_terms = 256
    !> Longest text a namelist string may hold (file paths)
    integer, parameter :: max_text = 1023

    !> The text of one group, as lines (an internal file: a namelist may span lines)
    type :: group_text_t
        character(len=:), allocatable :: name       !! group name, lower case
        character(len=:), allocatable :: text       !! '&name ... /' as in the file ('' when absent)
        character(len=:), allocatable :: body       !! the text between '&name' and '/'
    end type group_text_t

    abstract interface
        !> Read `lines` (one group holding one assignment) into a scratch copy of the group's
        !> variables; `stat` and `msg` as from read(nml=)
        subroutine try_interface(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
        end subroutine try_interface
    end interface

contains

    !> The groups of a namelist file. Refused: a file that is not text, no group at all, a group
    !> veslide does not read (misspelt), a group given twice, a group without its closing '/',
    !> and anything but blanks and '!' comments outside groups.
    subroutine scan_namelist(path, text, known, groups, error)
        character(len=*), intent(in) :: path, text, known(:)
        type(group_text_t), allocatable, intent(out) :: groups(:)
        type(error_t), allocatable, intent(out) :: error
        character(len=1) :: quote, c
        integer :: i, j, start, k, line
        logical :: comment, inside
        character(len=:), allocatable :: name, at, known_list
        allocate (groups(0))
        at = "veslide: "//path//": "
        known_list = "&"//trim(known(1))
        do k = 2, size(known)
            known_list = known_list//", &"//trim(known(k))
        end do
        do i = 1, len(text)
            c = text(i:i)
            if (iachar(c) < 32 .and. all(iachar(c) /= [9, 10, 13])) then
                call fatal_error(error, at//"not a text file (a control character at byte "//str(i)// &
                                 "): give a namelist file of groups "//known_list); return
            end if
        end do
        quote = ' '; comment = .false.; inside = .false.; line = 1; start = 0
        i = 1
        do while (i <= len(text))
            c = text(i:i)
            if (c == new_line('a')) then
                comment = .false.; line = line + 1
            else if (comment) then
                continue
            else if (quote /= ' ') then
                if (c == quote) quote = ' '
            else if (c == '!') then
                comment = .true.
            else if (inside) then
                if (c == '"' .or. c == "'") then
                    quote = c
                else if (c == '/') then
                    call close_group(i); if (allocated(error)) return
                    inside = .false.
                else if (c == '&') then
                    call fatal_error(error, at//"&"//name//" has no closing '/' before line "//str(line)); return
                end if
            else if (c == '&') then
                j = i + 1
                do while (j <= len(text))
                    if (index('abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_', text(j:j)) == 0) exit
                    j = j + 1
                end do
                name = lower(text(i + 1:j - 1))
                if (name_index(name, known) == 0) then
                    call fatal_error(error, at//"unknown namelist group &"//text(i + 1:j - 1)//" (known: "// &
                                     known_list//")"); return
                end if
                do k = 1, size(groups)
                    if (groups(k)%name == name) then
                        call fatal_error(error, at//"&"//name//" is given twice (line "//str(line)// &
                                         "): give each group once"); return
                    end if
                end do
                inside = .true.; start = i
                i = j - 1
            else if (c /= ' ' .and. iachar(c) /= 9 .and. iachar(c) /= 13) then
                call fatal_error(error, at//"text outside any namelist group at line "//str(line)// &
                                 " ('"//first_word(text(i:))//"'): groups start with &name and end with /"); return
            end if
            i = i + 1
        end do
        if (inside) then
            call fatal_error(error, at//"&"//name//" has no closing '/'"); return
        end if
        if (size(groups) == 0) then
            call fatal_error(error, at//"no namelist group found (a namelist file holds groups such as "// &
                             "&grid nx = 256 /; known: "//known_list//")"); return
        end if

    contains

        subroutine close_group(i_end)
            integer, intent(in) :: i_end
            type(group_text_t) :: g
            type(group_text_t), allocatable :: more(:)
            integer :: m
            g%name = name
            g%body = text(start + 1 + len(name):i_end - 1)
            g%text = text(start:i_end)
            allocate (more(size(groups) + 1))
            do m = 1, size(groups)
                more(m) = groups(m)
            end do
            more(size(more)) = g
            call move_alloc(more, groups)
        end subroutine close_group

    end subroutine scan_namelist

    !> The first blank-delimited word of s (at most 20 characters)
    pure function first_word(s) result(w)
        character(len=*), intent(in) :: s
        character(len=:), allocatable :: w
        integer :: k
        k = scan(s, ' '//new_line('a')//achar(9)//achar(13))
        if (k == 0) k = len(s) + 1
        w = s(1:min(k - 1, 20))
    end function first_word

    !> Lines of a text (split at newlines), all of the longest line's length: the internal file
    !> a group is read from (one blank line for an empty text: the read hits its end)
    pure subroutine split_lines(text, lines)
        character(len=*), intent(in) :: text
        character(len=:), allocatable, intent(out) :: lines(:)
        integer :: n, k, i0, i, w
        n = 1; w = 0; i0 = 1
        do i = 1, len(text)
            if (text(i:i) == new_line('a')) then
                n = n + 1; w = max(w, i - i0); i0 = i + 1
            end if
        end do
        w = max(w, len(text) - i0 + 1, 1)
        allocate (character(len=w) :: lines(n))
        k = 1; i0 = 1
        do i = 1, len(text)
            if (text(i:i) == new_line('a')) then
                lines(k) = text(i0:i - 1); k = k + 1; i0 = i + 1
            end if
        end do
        lines(k) = text(i0:)
    end subroutine split_lines

    !> The group named `name` among `groups`, or an empty one when absent (an internal read of
    !> it hits the end of file: the defaults apply)
    pure function get_group(groups, name) result(g)
        type(group_text_t), intent(in) :: groups(:)
        character(len=*), intent(in) :: name
        type(group_text_t) :: g
        integer :: k
        do k = 1, size(groups)
            if (groups(k)%name == name) then
                g = groups(k); return
            end if
        end do
        g%name = name; g%body = ''; g%text = ''
    end function get_group

    !> Did read(nml=) fail other than by the group being absent?
    elemental logical function read_failed(stat) result(yes)
        integer, intent(in) :: stat
        yes = stat /= 0 .and. .not. is_iostat_end(stat)
    end function read_failed

    !> After a failed read of group `group` (status stat /= 0, not the end of file): find the
    !> assignment that fails, alone, and say what is wrong with it. `names` are the group's
    !> variables and `kinds` what each holds ('an integer', 'a real number', ...).
    subroutine diagnose_read(stat, msg, path, group, body, names, kinds, try, error)
        integer, intent(in) :: stat
        character(len=*), intent(in) :: msg, path, group, body, names(:), kinds(:)
        procedure(try_interface) :: try
        type(error_t), allocatable, intent(out) :: error
        integer, allocatable :: starts(:)
        character(len=:), allocatable :: item, var, value, at
        character(len=512) :: msg1
        integer :: k, s1, e1, iv, st
        if (stat == 0 .or. is_iostat_end(stat)) return
        at = "veslide: "//path//": &"//group//" "
        call assignment_starts(body, starts)
        do k = 1, size(starts)
            s1 = starts(k)
            e1 = len(body); if (k < size(starts)) e1 = starts(k + 1) - 1
            item = trim(adjustl(body(s1:e1)))
            do while (len(item) > 0)
                if (item(len(item):len(item)) /= ',') exit
                item = trim(item(1:len(item) - 1))
            end do
            var = lower(trim(adjustl(item(1:index(item, '=') - 1))))
            if (index(var, '(') > 0) var = trim(var(1:index(var, '(') - 1))
            value = one_line(item(index(item, '=') + 1:))
            iv = name_index(var, names)
            if (iv == 0) then
                call fatal_error(error, at//var//": no such variable (the variables of &"//group//": "// &
                                 join(names)//")"); return
            end if
            call try(["&"//group//" "//item//" /"], st, msg1)
            if (st /= 0 .and. .not. is_iostat_end(st)) then
                call fatal_error(error, at//var//" = "//short(value)//" cannot be read: "//trim(kinds(iv))// &
                                 " is expected"); return
            end if
        end do
        if (size(starts) == 0 .and. len_trim(body) > 0) then
            call fatal_error(error, at//"holds no 'variable = value' (the variables of &"//group//": "// &
                             join(names)//")"); return
        end if
        call fatal_error(error, at//"cannot be read: "//trim(msg)//" (the variables of &"//group//": "// &
                         join(names)//")")
    contains
        !> A long value (a list) as its first 48 characters and its count of values
        pure function short(text) result(s)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: s
            integer :: j, n
            if (len(text) <= 72) then
                s = text; return
            end if
            n = 1
            do j = 1, len(text)
                if (text(j:j) == ',') n = n + 1
            end do
            s = text(1:48)//" ... ("//str(n)//" values)"
        end function short

        !> The value as one line of a message: without its comment, line ends and trailing commas
        pure function one_line(text) result(s)
            character(len=*), intent(in) :: text
            character(len=:), allocatable :: s
            character(len=1) :: quote
            integer :: j
            s = text; quote = ' '
            do j = 1, len(s)
                if (quote /= ' ') then
                    if (s(j:j) == quote) quote = ' '
                else if (s(j:j) == '"' .or. s(j:j) == "'") then
                    quote = s(j:j)
                else if (s(j:j) == '!') then
                    s = s(1:j - 1); exit
                end if
                if (iachar(s(j:j)) < 32) s(j:j) = ' '
            end do
            s = trim(adjustl(s))
            do while (len(s) > 0)
                if (s(len(s):len(s)) /= ',') exit
                s = trim(s(1:len(s) - 1))
            end do
        end function one_line

        pure function join(list) result(s)
            character(len=*), intent(in) :: list(:)
            character(len=:), allocatable :: s
            integer :: j
            s = trim(list(1))
            do j = 2, size(list)
                s = s//", "//trim(list(j))
            end do
        end function join
    end subroutine diagnose_read

    !> Where each 'name =' or 'name(i) =' of a group body starts (outside quotes and comments)
    pure subroutine assignment_starts(body, starts)
        character(len=*), intent(in) :: body
        integer, allocatable, intent(out) :: starts(:)
        integer :: i, j
        character(len=1) :: quote
        logical :: comment, boundary
        character(len=*), parameter :: word = 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
        allocate (starts(0))
        quote = ' '; comment = .false.; boundary = .true.
        i = 1
        do while (i <= len(body))
            if (body(i:i) == new_line('a')) then
                comment = .false.; boundary = .true.
            else if (comment) then
                continue
            else if (quote /= ' ') then
                if (body(i:i) == quote) quote = ' '
            else if (body(i:i) == '"' .or. body(i:i) == "'") then
                quote = body(i:i); boundary = .false.
            else if (body(i:i) == '!') then
                comment = .true.
            else if (index(word, body(i:i)) > 0 .and. boundary .and. verify(body(i:i), '0123456789') /= 0) then
                j = i
                do while (j <= len(body))
                    if (index(word, body(j:j)) == 0) exit
                    j = j + 1
                end do
                if (j <= len(body)) then
                    if (body(j:j) == '(') j = j + index(body(j:), ')')
                end if
                do while (j <= len(body))
                    if (body(j:j) /= ' ') exit
                    j = j + 1
                end do
                if (j <= len(body)) then
                    if (body(j:j) == '=') starts = [starts, i]
                end if
                boundary = .false.
                i = j - 1
            else
                boundary = index(' ,'//achar(9)//achar(13), body(i:i)) > 0
            end if
            i = i + 1
        end do
    end subroutine assignment_starts

    !> The variables a group body assigns, lower case, each once, in the order first assigned
    !> ('name(2) = ...' counts as 'name'): what the input gave, whatever the value
    pure subroutine assigned_names(body, names)
        character(len=*), intent(in) :: body
        character(len=:), allocatable, intent(out) :: names(:)
        integer, allocatable :: starts(:)
        character(len=32), allocatable :: found(:)
        character(len=32) :: name
        integer :: k, e, w
        character(len=*), parameter :: word = 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
        call assignment_starts(body, starts)
        allocate (found(0))
        do k = 1, size(starts)
            e = starts(k)
            w = verify(body(e:), word)
            if (w == 0) then
                name = lower(body(e:))
            else
                name = lower(body(e:e + w - 2))
            end if
            if (all(found /= name)) found = [character(len=32) :: found, name]
        end do
        allocate (character(len=32) :: names(size(found)))
        names = found
    end subroutine assigned_names

    !> The refusal "veslide: PATH: &GROUP VAR = VALUE is out of range (allowed: ALLOWED)"
    pure subroutine range_error(error, path, group, var, value, allowed)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in) :: path, group, var, value, allowed
        call fatal_error(error, "veslide: "//path//": &"//group//" "//var//" = "//value// &
            " is out of range (allowed: "//allowed//")")
    end subroutine range_error

    !> range_error unless `ok`; a no-op when an error is already set (so checks can be chained)
    pure subroutine require(error, ok, path, group, var, value, allowed)
        type(error_t), allocatable, intent(inout) :: error
        logical, intent(in) :: ok
        character(len=*), intent(in) :: path, group, var, value, allowed
        if (allocated(error) .or. ok) return
        call range_error(error, path, group, var, value, allowed)
    end subroutine require

    !> Is x finite and lo <= x <= hi (or lo < x when `open_low`)?
    elemental logical function finite_in(x, lo, hi, open_low) result(ok)
        real(dp), intent(in) :: x, lo, hi
        logical, intent(in), optional :: open_low
        ok = ieee_is_finite(x)
        if (.not. ok) return
        ok = x >= lo .and. x <= hi
        if (present(open_low)) then
            if (open_low) ok = x > lo .and. x <= hi
        end if
    end function finite_in

    !> "'a', 'b' or 'c'"
    pure function choices_text(names) result(s)
        character(len=*), intent(in) :: names(:)
        character(len=:), allocatable :: s
        integer :: k
        s = "'"//trim(names(1))//"'"
        do k = 2, size(names)
            if (k == size(names)) then
                s = s//" or '"//trim(names(k))//"'"
            else
                s = s//", '"//trim(names(k))//"'"
            end if
        end do
    end function choices_text

    pure logical function is_one_of(value, names) result(yes)
        character(len=*), intent(in) :: value, names(:)
        yes = name_index(value, names) > 0
    end function is_one_of

    !> The value that marks an unset entry of a real list: a NaN with a payload no input produces
    pure real(dp) function unset_real() result(x)
        x = transfer(int(z'7FF8DEC0DE5E7001', i8), 1.0_dp)
    end function unset_real

    elemental logical function is_unset(x) result(yes)
        real(dp), intent(in) :: x
        yes = transfer(x, 0_i8) == int(z'7FF8DEC0DE5E7001', i8)
    end function is_unset

    !> Number of leading set entries of a list
    pure integer function list_length(x) result(n)
        real(dp), intent(in) :: x(:)
        n = 0
        do while (n < size(x))
            if (is_unset(x(n + 1))) exit
            n = n + 1
        end do
    end function list_length

    !> A list must be contiguous (no unset entry before a set one) and every entry finite
    subroutine check_list(error, x, path, group, var)
        type(error_t), allocatable, intent(inout) :: error
        real(dp), intent(in) :: x(:)
        character(len=*), intent(in) :: path, group, var
        integer :: n, k
        if (allocated(error)) return
        n = list_length(x)
        do k = n + 1, size(x)
            if (.not. is_unset(x(k))) then
                call fatal_error(error, "veslide: "//path//": &"//group//" "//var//" has a gap (entry "//str(n + 1)// &
                                 " unset, entry "//str(k)//" set): give a contiguous list"); return
            end if
        end do
        do k = 1, n
            if (.not. ieee_is_finite(x(k))) then
                call fatal_error(error, "veslide: "//path//": &"//group//" "//var//"("//str(k)//") is not finite"); return
            end if
        end do
    end subroutine check_list

    !> A text read into a buffer of max_text + 1 characters must not have filled it, and its value
    !> as written in the group's `body` (the last assignment of `var`, quotes undone) must not be
    !> longer than max_text either: a value whose blanks run past the buffer before more text is
    !> cut by the read to what fits, which the buffer alone cannot tell
    subroutine check_text_length(error, text, path, group, var, body)
        type(error_t), allocatable, intent(inout) :: error
        character(len=*), intent(in) :: text, path, group, var, body
        if (allocated(error)) return
        if (len_trim(text) >= len(text) .or. written_length(body, var) > len(text) - 1) &
            call fatal_error(error, "veslide: "//path//": &"//group//" "//var//" is longer than "// &
                             str(len(text) - 1)//" characters")
    end subroutine check_text_length

    !> The length of the quoted text last assigned to `var` in a group body (a doubled quote
    !> counts once); 0 when it is not assigned a quoted text
    pure integer function written_length(body, var) result(n)
        character(len=*), intent(in) :: body, var
        integer, allocatable :: starts(:)
        integer :: k, i, e
        character(len=1) :: q
        n = 0
        call assignment_starts(body, starts)
        do k = 1, size(starts)
            e = index(body(starts(k):), '=') + starts(k) - 1
            if (lower(trim(adjustl(body(starts(k):e - 1)))) /= lower(var)) cycle
            i = e + 1
            do while (i <= len(body))
                if (body(i:i) /= ' ' .and. iachar(body(i:i)) >= 32) exit
                i = i + 1
            end do
            if (i > len(body)) exit
            q = body(i:i)
            if (q /= '"' .and. q /= "'") cycle
            n = 0; i = i + 1
            do while (i <= len(body))
                if (body(i:i) == q) then
                    if (i < len(body)) then
                        if (body(i + 1:i + 1) == q) then       ! a doubled quote: one character
                            n = n + 1; i = i + 2; cycle
                        end if
                    end if
                    exit
                end if
                n = n + 1; i = i + 1
            end do
        end do
    end function written_length

end module veslide_config_common
