!> &output: where the result goes and what it holds
module veslide_config_output
    use veslide_error, only: error_t
    use veslide_config_common, only: namelist_status, require
    implicit none
    private
    public :: output_config_t, read_output_config

    type :: output_config_t
        character(len=:), allocatable :: file      !! result file
        logical :: fields = .true.                 !! write the 2-D fields
        logical :: overwrite = .false.             !! replace an existing file
    end type output_config_t

contains

    subroutine read_output_config(self, u, path, error)
        type(output_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=1024) :: file
        logical :: fields, overwrite
        integer :: stat
        character(len=512) :: msg
        namelist /output/ file, fields, overwrite
        file = 'veslide.h5'; fields = self%fields; overwrite = self%overwrite
        rewind (u); read (u, nml=output, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'output', error); if (allocated(error)) return
        self%file = trim(file); self%fields = fields; self%overwrite = overwrite
        call require(error, len(self%file) > 0, path, 'output', 'file', "''", "a file path")
    end subroutine read_output_config

end module veslide_config_output
