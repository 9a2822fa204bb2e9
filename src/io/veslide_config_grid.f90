!> &grid: the periodic cell and its points
module veslide_config_grid
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in
    implicit none
    private
    public :: grid_config_t, read_grid_config

    type :: grid_config_t
        integer :: nx = 256, ny = 256      !! points along x and y
        real(dp) :: lx_m = 0.0_dp          !! cell side along x [m]; 0: 0.01, or the height file's length_m
        real(dp) :: ly_m = 0.0_dp          !! cell side along y [m]; 0: lx_m*ny/nx
        logical :: nx_given = .false., ny_given = .false.   !! the input set nx, ny
    end type grid_config_t

    character(len=*), parameter :: names(4) = [character(len=4) :: 'nx', 'ny', 'lx_m', 'ly_m']
    character(len=*), parameter :: kinds(4) = [character(len=13) :: 'an integer', 'an integer', &
                                               'a real number', 'a real number']

contains

    !> Read &grid from its text (absent: defaults) and check it
    subroutine read_grid_config(self, g, path, error)
        type(grid_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        integer :: nx, ny, stat
        real(dp) :: lx_m, ly_m
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /grid/ nx, ny, lx_m, ly_m
        nx = self%nx; ny = self%ny; lx_m = self%lx_m; ly_m = self%ly_m
        call split_lines(g%text, lines)
        read (lines, nml=grid, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'grid', g%body, names, kinds, try, error); return
        end if
        self%nx = nx; self%ny = ny; self%lx_m = lx_m; self%ly_m = ly_m
        call require(error, nx >= 1 .and. nx <= 65536, path, 'grid', 'nx', str(nx), "1 to 65536")
        call require(error, ny >= 1 .and. ny <= 65536, path, 'grid', 'ny', str(ny), "1 to 65536")
        call require(error, nx*int(ny, i8) >= 2, path, 'grid', 'nx*ny', str(nx*int(ny, i8)), "at least 2 cells")
        call require(error, lx_m == 0.0_dp .or. finite_in(lx_m, 1.0e-9_dp, 1.0e3_dp), path, 'grid', 'lx_m', &
                     str(lx_m), "1e-9 to 1e3 [m], or 0 for the default (0.01, or the file's length_m)")
        call require(error, ly_m == 0.0_dp .or. finite_in(ly_m, 1.0e-9_dp, 1.0e3_dp), path, 'grid', 'ly_m', &
                     str(ly_m), "1e-9 to 1e3 [m], or 0 for lx_m*ny/nx")
        ! given when a read from another default gives the same value (an integer has no value
        ! to mark 'unset' that an input could not also give, unlike k_cut's NaN)
        nx = -1; ny = -1
        read (lines, nml=grid, iostat=stat, iomsg=msg)
        self%nx_given = nx == self%nx; self%ny_given = ny == self%ny
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            integer :: nx, ny
            real(dp) :: lx_m, ly_m
            namelist /grid/ nx, ny, lx_m, ly_m
            read (lines, nml=grid, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_grid_config

end module veslide_config_grid
