!> &analysis: what is derived from a solution beyond the always-reported quantities
module veslide_config_analysis
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in
    implicit none
    private
    public :: analysis_config_t, read_analysis_config

    type :: analysis_config_t
        logical :: anisotropy = .false.     !! slope tensors of surface and deformed solid, eq. (16)
        real(dp) :: zeta1 = 1.0_dp          !! lower band edge [2 pi/lx_m]
        real(dp) :: zeta2 = 0.0_dp          !! upper band edge [2 pi/lx_m]; 0: k_cut
        integer :: n_theta = 72             !! polar samples of m2, mu2
        real(dp) :: iso_tol = 1.0e-3_dp     !! 1 - gamma <= iso_tol counts as isotropic
        logical :: patches = .false.        !! contact patches and percolation
        logical :: persson = .false.        !! Persson's theory on the realised spectrum, beside the solve
        logical :: persson_correction = .false.  !! Persson's S(q) = 1/2 + P^2/2 instead of S = 1
    end type analysis_config_t

    character(len=*), parameter :: names(8) = [character(len=18) :: 'anisotropy', 'zeta1', 'zeta2', 'n_theta', &
        'iso_tol', 'patches', 'persson', 'persson_correction']
    character(len=*), parameter :: kinds(8) = [character(len=29) :: 'a logical (.true. or .false.)', &
        'a real number', 'a real number', 'an integer', 'a real number', 'a logical (.true. or .false.)', &
        'a logical (.true. or .false.)', 'a logical (.true. or .false.)']

contains

    !> Read &analysis from its text (absent: defaults) and check what does not depend on the
    !> surface (zeta2 = 0 is resolved by the configuration)
    subroutine read_analysis_config(self, g, path, error)
        type(analysis_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        logical :: anisotropy, patches, persson, persson_correction
        real(dp) :: zeta1, zeta2, iso_tol
        integer :: n_theta, stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /analysis/ anisotropy, zeta1, zeta2, n_theta, iso_tol, patches, persson, persson_correction
        anisotropy = self%anisotropy; zeta1 = self%zeta1; zeta2 = self%zeta2; n_theta = self%n_theta
        iso_tol = self%iso_tol; patches = self%patches; persson = self%persson
        persson_correction = self%persson_correction
        call split_lines(g%text, lines)
        read (lines, nml=analysis, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'analysis', g%body, names, kinds, try, error); return
        end if
        self%anisotropy = anisotropy; self%zeta1 = zeta1; self%zeta2 = zeta2; self%n_theta = n_theta
        self%iso_tol = iso_tol; self%patches = patches; self%persson = persson
        self%persson_correction = persson_correction
        call require(error, n_theta >= 4 .and. n_theta <= 100000, path, 'analysis', 'n_theta', str(n_theta), &
                     "4 to 100000")
        call require(error, finite_in(iso_tol, 0.0_dp, 1.0_dp) .and. iso_tol < 1.0_dp, path, 'analysis', 'iso_tol', &
                     str(iso_tol), "0 <= iso_tol < 1")
        call require(error, finite_in(zeta1, 0.0_dp, 1.0e6_dp) .and. finite_in(zeta2, 0.0_dp, 1.0e6_dp), path, &
                     'analysis', 'zeta1/zeta2', str(zeta1)//"/"//str(zeta2), "finite, 0 to 1e6")
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            logical :: anisotropy, patches, persson, persson_correction
            real(dp) :: zeta1, zeta2, iso_tol
            integer :: n_theta
            namelist /analysis/ anisotropy, zeta1, zeta2, n_theta, iso_tol, patches, persson, persson_correction
            read (lines, nml=analysis, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_analysis_config

end module veslide_config_analysis
