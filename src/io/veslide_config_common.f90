!> What every namelist group shares: the status of a namelist read, and refusals that name the
!> file, the group, the variable, the value and the allowed range.
module veslide_config_common
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: name_index
    implicit none
    private
    public :: namelist_status, range_error, require, choices_text, is_one_of, max_list

    !> Longest list a namelist array may hold (Prony terms, sweep lists)
    integer, parameter :: max_list = 64

contains

    !> After `read (u, nml=group, iostat=stat, iomsg=msg)`: an absent group (end of file) is not an
    !> error (the defaults apply); any other failure is, named by file and group
    subroutine namelist_status(stat, msg, path, group, error)
        integer, intent(in) :: stat
        character(len=*), intent(in) :: msg, path, group
        type(error_t), allocatable, intent(out) :: error
        if (stat == 0 .or. is_iostat_end(stat)) return
        call fatal_error(error, "veslide: "//path//": &"//group//": "//trim(msg)// &
            " (check the variable names and values of &"//group//")")
    end subroutine namelist_status

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

end module veslide_config_common
