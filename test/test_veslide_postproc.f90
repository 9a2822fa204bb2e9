!> The figure scripts of postproc/ run (headless) on small studies made here, and draw every figure;
!> the speed studies (figures 4-7) carry Persson's theory, which the script must draw beside them
module test_veslide_postproc
    use veslide_error, only: fatal_error
    use veslide_config, only: config_t, read_config
    use veslide_case, only: case_t, run_case
    use veslide_case_file, only: write_case
    use veslide_study, only: run_study
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use test_support, only: unique_name, write_text
    implicit none
    private
    public :: collect_postproc

contains

    subroutine collect_postproc(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [new_unittest("paper-figures-from-small-studies", test_figures)]
    end subroutine collect_postproc

    subroutine test_figures(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: dir, base, pbase, python
        character(len=*), parameter :: figs(8) = [character(len=25) :: 'fig1.png', 'fig2.png', 'fig3.png', &
            'fig4.png', 'fig5.png', 'fig6.png', 'fig7.png', 'fig8_stretch_rotation.png']
        character(len=256) :: buf
        integer :: stat, cstat, k, n
        logical :: exists
        dir = unique_name('figs')
        call execute_command_line('mkdir -p '//dir//'/out', exitstat=stat)
        base = "&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.6 / &material model='one_term' /"// &
               " &solver fft_planner='estimate', tolerance = 1e-8 / &analysis anisotropy = .true."
        pbase = base//", persson = .true. /"
        base = base//" /"
        call single('fig1', base//" &motion speed_m_s = 0.13 /", .true., error); if (allocated(error)) return
        call study('fig2', base//" &motion speed_m_s = 0.13 / &sweep n_seeds = 2 /", error)
        if (allocated(error)) return
        call study('fig3', base//" &motion speed_m_s = 0.13 / &sweep alphas_deg = 0, 45, 90, n_seeds = 2 /", error)
        if (allocated(error)) return
        call study('fig4_5_7', pbase//" &sweep speeds_m_s = 0.01, 0.1, 1, alphas_deg = 0, 90, n_seeds = 2 /", error)
        if (allocated(error)) return
        call study('fig6', pbase//" &sweep speeds_m_s = 0.01, 0.1, eccentricities = 1, 0.5 /", error)
        if (allocated(error)) return
        python = 'python3'
        call get_environment_variable('VESLIDE_PYTHON', buf, n, stat)
        if (stat == 0 .and. n > 0) python = trim(buf)
        call execute_command_line(python//' postproc/make_figures.py '//dir//' '//dir//'/out > '//dir// &
                                  '/log.txt 2>&1', exitstat=stat, cmdstat=cstat)
        call check(error, cstat == 0 .and. stat == 0, "postproc/make_figures.py failed (see "//dir//"/log.txt)")
        if (allocated(error)) return
        do k = 1, size(figs)
            inquire (file=dir//'/out/'//trim(figs(k)), exist=exists)
            if (.not. exists) then
                call fatal_error(error, "no "//trim(figs(k))); return
            end if
        end do
        do k = 4, 7                                  ! the script reports each figure it drew the theory in
            call check(error, log_has(dir//'/log.txt', 'out/'//trim(figs(k))//" (with Persson's theory)"), &
                       trim(figs(k))//" drawn without Persson's theory (see "//dir//"/log.txt)")
            if (allocated(error)) return
        end do
        call execute_command_line('rm -rf '//dir)

    contains

        subroutine single(name, text, fields, error)
            character(len=*), intent(in) :: name, text
            logical, intent(in) :: fields
            type(error_t), allocatable, intent(out) :: error
            type(config_t) :: cfg
            type(case_t) :: c
            call write_text(dir//'/'//name//'.nml', text)
            call read_config(dir//'/'//name//'.nml', cfg, error); if (allocated(error)) return
            cfg%output%fields = fields
            call run_case(cfg, c, error); if (allocated(error)) return
            call write_case(dir//'/'//name//'.h5', c, error)
        end subroutine single

        !> whether a line of the text file `path` contains `text`
        logical function log_has(path, text) result(found)
            character(len=*), intent(in) :: path, text
            character(len=1024) :: line
            integer :: u, ios
            found = .false.
            open (newunit=u, file=path, status='old', action='read', iostat=ios)
            if (ios /= 0) return
            do
                read (u, '(a)', iostat=ios) line
                if (ios /= 0) exit
                if (index(line, text) > 0) then
                    found = .true.; exit
                end if
            end do
            close (u)
        end function log_has

        subroutine study(name, text, error)
            character(len=*), intent(in) :: name, text
            type(error_t), allocatable, intent(out) :: error
            type(config_t) :: cfg
            integer :: nfail
            call write_text(dir//'/'//name//'.nml', text)
            call read_config(dir//'/'//name//'.nml', cfg, error); if (allocated(error)) return
            cfg%output%fields = .false.
            call run_study(cfg, dir//'/'//name//'.h5', nfail, error)
        end subroutine study

    end subroutine test_figures

end module test_veslide_postproc
