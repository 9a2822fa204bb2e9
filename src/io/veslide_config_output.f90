!> &output: where the result goes and what it holds
module veslide_config_output
    use veslide_error, only: error_t
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, check_text_length, max_text
    implicit none
    private
    public :: output_config_t, read_output_config

    type :: output_config_t
        !> result file (default: the namelist's name with '.h5', in the current directory)
        character(len=:), allocatable :: file
        !> write the 2-D fields: by default for a single case, not for a study (18 cases of 512^2
        !> are 151 MB with them, 391 kB without); `fields = .true.` asks for them in a study
        logical :: fields = .true.
        logical :: fields_given = .false.          !! the input set `fields`
        logical :: overwrite = .false.             !! replace an existing file
    end type output_config_t

    character(len=*), parameter :: names(3) = [character(len=9) :: 'file', 'fields', 'overwrite']
    character(len=*), parameter :: kinds(3) = [character(len=32) :: "a quoted text ('out.h5')", &
                                               'a logical (.true. or .false.)', 'a logical (.true. or .false.)']

contains

    subroutine read_output_config(self, g, path, error)
        type(output_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=max_text + 1) :: file
        logical :: fields, overwrite
        integer :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /output/ file, fields, overwrite
        file = achar(0); fields = self%fields; overwrite = self%overwrite
        call split_lines(g%text, lines)
        read (lines, nml=output, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'output', g%body, names, kinds, try, error); return
        end if
        call check_text_length(error, file, path, 'output', 'file', g%body); if (allocated(error)) return
        if (file == achar(0)) file = default_output(path)
        self%file = trim(file); self%fields = fields; self%overwrite = overwrite
        ! given when a read with the opposite default gives the same value
        fields = .not. self%fields
        read (lines, nml=output, iostat=stat, iomsg=msg)
        self%fields_given = stat == 0 .and. (fields .eqv. self%fields)
        call require(error, len(self%file) > 0, path, 'output', 'file', "''", "a file path")
    contains
        !> The namelist file's name, its directory and extension dropped, with '.h5': the result of
        !> case.nml is case.h5 in the current directory (veslide.h5 for a name that leaves nothing)
        function default_output(input) result(out)
            character(len=*), intent(in) :: input
            character(len=:), allocatable :: out
            integer :: slash, dot
            slash = index(input, '/', back=.true.)
            out = input(slash + 1:)
            dot = index(out, '.', back=.true.)
            if (dot > 1) out = out(:dot - 1)
            if (len(out) == 0 .or. out == '.' .or. out == '..') out = 'veslide'
            out = out//'.h5'
        end function default_output

        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            character(len=max_text + 1) :: file
            logical :: fields, overwrite
            namelist /output/ file, fields, overwrite
            read (lines, nml=output, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_output_config

end module veslide_config_output
