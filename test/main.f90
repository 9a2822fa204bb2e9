!> Runs all test suites, or one suite, or one test: `fpm test -- [suite [test]]`.
!> Ends with the line "N passed, N failed"; exits non-zero when anything failed.
!> One suite per library module (config groups included), in the order of the layers.
program veslide_tests
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit, stderr => error_unit
    use testsuite, only: testsuite_t, new_testsuite, run_testsuite
    use test_support, only: unique_name
    use test_veslide_rng, only: collect_rng
    use test_veslide_grid, only: collect_grid, collect_fftw
    use test_veslide_threads, only: collect_threads
    use test_veslide_material, only: collect_material
    use test_veslide_kernel, only: collect_kernel
    use test_veslide_surface, only: collect_surface
    use test_veslide_contact, only: collect_contact, collect_quantities, collect_analysis
    use test_veslide_contact_law, only: collect_contact_law
    use test_veslide_solver_table, only: collect_solver_table
    use test_veslide_anderson, only: collect_anderson
    use test_veslide_solver_pk, only: collect_solver_pk
    use test_veslide_solver_dr, only: collect_solver_dr
    use test_veslide_solver_gcg, only: collect_solver_gcg
    use test_veslide_solver_bccg, only: collect_solver_bccg
    use test_veslide_solver_pdr, only: collect_solver_pdr
    use test_veslide_anisotropy, only: collect_anisotropy
    use test_veslide_persson, only: collect_persson
    use test_veslide_hdf5, only: collect_hdf5
    use test_veslide_config, only: collect_config, collect_config_grid, collect_config_surface, &
                                   collect_config_material, collect_config_load, collect_config_motion, &
                                   collect_config_solver, collect_config_analysis, collect_config_sweep, &
                                   collect_config_output, collect_config_interface
    use test_veslide_topography, only: collect_topography
    use test_veslide_output, only: collect_output
    use test_veslide_case, only: collect_case
    use test_veslide_study, only: collect_study
    use test_veslide_hard, only: collect_hard
    use test_veslide_validity, only: collect_validity
    use test_veslide_device, only: collect_device
    use test_veslide_postproc, only: collect_postproc
    implicit none
    type(testsuite_t), allocatable :: suites(:)
    character(len=128) :: want_suite, want_test
    integer :: i, npass, nfail, nrun

    suites = [ &
        new_testsuite("rng", collect_rng), &
        new_testsuite("grid", collect_grid), &
        new_testsuite("fftw", collect_fftw), &
        new_testsuite("threads", collect_threads), &
        new_testsuite("material", collect_material), &
        new_testsuite("kernel", collect_kernel), &
        new_testsuite("surface", collect_surface), &
        new_testsuite("contact", collect_contact), &
        new_testsuite("contact-law", collect_contact_law), &
        new_testsuite("anderson", collect_anderson), &
        new_testsuite("solver-pk", collect_solver_pk), &
        new_testsuite("solver-dr", collect_solver_dr), &
        new_testsuite("solver-gcg", collect_solver_gcg), &
        new_testsuite("solver-bccg", collect_solver_bccg), &
        new_testsuite("solver-pdr", collect_solver_pdr), &
        new_testsuite("solver-table", collect_solver_table), &
        new_testsuite("analysis", collect_analysis), &
        new_testsuite("anisotropy", collect_anisotropy), &
        new_testsuite("persson", collect_persson), &
        new_testsuite("quantities", collect_quantities), &
        new_testsuite("hdf5", collect_hdf5), &
        new_testsuite("config", collect_config), &
        new_testsuite("config-grid", collect_config_grid), &
        new_testsuite("config-surface", collect_config_surface), &
        new_testsuite("config-material", collect_config_material), &
        new_testsuite("config-load", collect_config_load), &
        new_testsuite("config-motion", collect_config_motion), &
        new_testsuite("config-interface", collect_config_interface), &
        new_testsuite("config-solver", collect_config_solver), &
        new_testsuite("config-analysis", collect_config_analysis), &
        new_testsuite("config-sweep", collect_config_sweep), &
        new_testsuite("config-output", collect_config_output), &
        new_testsuite("topography", collect_topography), &
        new_testsuite("output", collect_output), &
        new_testsuite("case", collect_case), &
        new_testsuite("study", collect_study), &
        new_testsuite("hard", collect_hard), &
        new_testsuite("validity", collect_validity), &
        new_testsuite("device", collect_device), &
        new_testsuite("postproc", collect_postproc) &
        ]
    want_suite = ''; want_test = ''
    if (command_argument_count() >= 1) call get_command_argument(1, want_suite)
    if (command_argument_count() >= 2) call get_command_argument(2, want_test)
    npass = 0; nfail = 0; nrun = 0
    do i = 1, size(suites)
        if (len_trim(want_suite) > 0 .and. suites(i)%name /= trim(want_suite)) cycle
        nrun = nrun + 1
        call run_testsuite(suites(i), npass, nfail, trim(want_test))
    end do
    if (nrun == 0 .or. npass + nfail == 0) then
        write (stderr, '(a)') "no test matches '"//trim(want_suite)//" "//trim(want_test)//"'"
        nfail = nfail + 1
    end if
    call check_no_leftovers()
    write (stdout, '(i0,a,i0,a)') npass, " passed, ", nfail, " failed"
    if (nfail > 0) error stop 1

contains

    !> Every file a test made under its unique names (test_support's unique_name) is gone: the
    !> suite leaves nothing in the temporary directory (a run of the whole suite counts a failure
    !> when it does, naming the files)
    subroutine check_no_leftovers()
        character(len=:), allocatable :: prefix, listing
        integer :: stat, u, n
        character(len=512) :: line
        prefix = unique_name('')
        stat = 0
        listing = unique_name('leftovers.txt')
        call execute_command_line("ls -d "//prefix//"* 2>/dev/null | grep -v -x '"//listing//"' > "//listing, &
                                  exitstat=stat)
        n = 0
        open (newunit=u, file=listing, status='old', action='read', iostat=stat)
        if (stat /= 0) return
        do
            read (u, '(a)', iostat=stat) line
            if (stat /= 0) exit
            n = n + 1
            write (stderr, '(a)') "  LEFT  "//trim(line)//" (a test left this file in the temporary directory)"
        end do
        close (u, status='delete')
        if (n > 0 .and. len_trim(want_suite) == 0) nfail = nfail + 1
    end subroutine check_no_leftovers
end program veslide_tests
