!> &grid: the periodic cell and its points
module veslide_config_grid
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: namelist_status, require
    implicit none
    private
    public :: grid_config_t, read_grid_config

    type :: grid_config_t
        integer :: nx = 256, ny = 256      !! points along x and y
        real(dp) :: lx_m = 0.0_dp          !! cell side along x [m]; 0: 0.01, or the height file's length_m
        real(dp) :: ly_m = 0.0_dp          !! cell side along y [m]; 0: lx_m*ny/nx
    end type grid_config_t

contains

    !> Read &grid from the open namelist file `u` (absent: defaults) and check it
    subroutine read_grid_config(self, u, path, error)
        type(grid_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        integer :: nx, ny, stat
        real(dp) :: lx_m, ly_m
        character(len=512) :: msg
        namelist /grid/ nx, ny, lx_m, ly_m
        nx = self%nx; ny = self%ny; lx_m = self%lx_m; ly_m = self%ly_m
        rewind (u); read (u, nml=grid, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'grid', error); if (allocated(error)) return
        self%nx = nx; self%ny = ny; self%lx_m = lx_m; self%ly_m = ly_m
        call require(error, nx >= 1 .and. nx <= 65536, path, 'grid', 'nx', str(nx), "1 to 65536")
        call require(error, ny >= 1 .and. ny <= 65536, path, 'grid', 'ny', str(ny), "1 to 65536")
        call require(error, nx*int(ny, i8) >= 2, path, 'grid', 'nx*ny', str(nx*int(ny, i8)), "at least 2 cells")
        call require(error, ieee_is_finite(lx_m) .and. lx_m >= 0.0_dp, path, 'grid', 'lx_m', str(lx_m), &
                     "> 0 [m], or 0 for the default (0.01, or the file's length_m)")
        call require(error, ieee_is_finite(ly_m) .and. ly_m >= 0.0_dp, path, 'grid', 'ly_m', str(ly_m), &
                     "> 0 [m], or 0 for lx_m*ny/nx")
    end subroutine read_grid_config

end module veslide_config_grid
