!> Runs all test suites, or one suite, or one test: `fpm test -- [suite [test]]`.
!> Ends with the line "N passed, N failed"; exits non-zero when anything failed.
program veslide_tests
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit, stderr => error_unit
    use testsuite, only: testsuite_t, new_testsuite, run_testsuite
    use test_veslide_solver, only: collect_solver
    use test_veslide_surface, only: collect_surface
    use test_veslide_config, only: collect_config
    use test_veslide_visco, only: collect_visco
    use test_veslide_hard, only: collect_hard
    use test_veslide_anisotropy, only: collect_anisotropy
    use test_veslide_postproc, only: collect_postproc
    implicit none
    type(testsuite_t), allocatable :: suites(:)
    character(len=128) :: want_suite, want_test
    integer :: i, npass, nfail, nrun

    suites = [ &
        new_testsuite("config", collect_config), &
        new_testsuite("surface", collect_surface), &
        new_testsuite("solver", collect_solver), &
        new_testsuite("visco", collect_visco), &
        new_testsuite("anisotropy", collect_anisotropy), &
        new_testsuite("hard", collect_hard), &
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
    write (stdout, '(i0,a,i0,a)') npass, " passed, ", nfail, " failed"
    if (nfail > 0) error stop 1
end program veslide_tests
