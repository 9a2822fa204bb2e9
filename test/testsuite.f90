!> A small unit-test harness in the mould of fortran-lang/test-drive: suites of named tests,
!> expected failures, tolerance checks; errors are veslide's own `error_t`.
module testsuite
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    implicit none
    private
    public :: error_t, unittest_t, testsuite_t, new_unittest, new_testsuite, run_testsuite, check, &
              test_interface, collect_interface, rel_error, report

    abstract interface
        subroutine test_interface(error)
            import :: error_t
            type(error_t), allocatable, intent(out) :: error
        end subroutine test_interface
    end interface

    type :: unittest_t
        character(len=:), allocatable :: name
        procedure(test_interface), pointer, nopass :: test => null()
        logical :: should_fail = .false.   !! the test passes when it returns an error ...
        character(len=:), allocatable :: expect   !! ... whose message contains this text
    end type unittest_t

    abstract interface
        subroutine collect_interface(tests)
            import :: unittest_t
            type(unittest_t), allocatable, intent(out) :: tests(:)
        end subroutine collect_interface
    end interface

    type :: testsuite_t
        character(len=:), allocatable :: name
        procedure(collect_interface), pointer, nopass :: collect => null()
    end type testsuite_t

    interface check
        module procedure check_logical, check_real, check_int
    end interface check

    !> Measurements a test reports (errors against oracles); printed after its result
    character(len=:), allocatable, save :: reported

contains

    !> Record a measured value for the test log, e.g. call report("peak error", 1.1e-3_dp)
    subroutine report(label, value)
        character(len=*), intent(in) :: label
        real(dp), intent(in) :: value
        character(len=32) :: buf
        write (buf, '(es10.3)') value
        if (.not. allocated(reported)) reported = ''
        reported = reported//' ['//label//' '//trim(adjustl(buf))//']'
    end subroutine report

    !> A named test; an expected failure (`should_fail`) passes only when the error it returns
    !> says `expect` (an expected failure without it never passes: any error would do)
    function new_unittest(name, test, should_fail, expect) result(self)
        character(len=*), intent(in) :: name
        procedure(test_interface) :: test
        logical, intent(in), optional :: should_fail
        character(len=*), intent(in), optional :: expect
        type(unittest_t) :: self
        self%name = name
        self%test => test
        self%should_fail = .false.
        if (present(should_fail)) self%should_fail = should_fail
        self%expect = ''
        if (present(expect)) self%expect = expect
    end function new_unittest

    function new_testsuite(name, collect) result(self)
        character(len=*), intent(in) :: name
        procedure(collect_interface) :: collect
        type(testsuite_t) :: self
        self%name = name
        self%collect => collect
    end function new_testsuite

    !> Run the tests of one suite (all, or the one named `only`); counts are added to
    subroutine run_testsuite(suite, npass, nfail, only)
        type(testsuite_t), intent(in) :: suite
        integer, intent(inout) :: npass, nfail
        character(len=*), intent(in), optional :: only
        type(unittest_t), allocatable :: tests(:)
        type(error_t), allocatable :: error
        integer :: i
        integer(8) :: c0, c1, rate
        logical :: ok
        character(len=:), allocatable :: note
        call suite%collect(tests)
        write (stdout, '(a)') "# suite "//suite%name
        do i = 1, size(tests)
            if (present(only)) then
                if (len(only) > 0 .and. tests(i)%name /= only) cycle
            end if
            reported = ''
            call system_clock(c0, rate)
            call tests(i)%test(error)
            call system_clock(c1)
            ok = allocated(error) .eqv. tests(i)%should_fail
            note = ''
            if (allocated(error)) note = error%message
            if (ok .and. tests(i)%should_fail) then
                if (len(tests(i)%expect) == 0) then
                    ok = .false.; note = 'expected failure without a message to check: '//note
                else if (index(note, tests(i)%expect) == 0) then
                    ok = .false.; note = "failed, but not saying '"//tests(i)%expect//"': "//note
                end if
            end if
            if (ok) then
                npass = npass + 1
                if (tests(i)%should_fail) note = 'expected failure: '//note
                write (stdout, '(a,f7.2,a)') "  PASS  "//suite%name//" "//tests(i)%name//" (", &
                    real(c1 - c0)/real(rate), " s) "//note//reported
            else
                nfail = nfail + 1
                if (tests(i)%should_fail .and. .not. allocated(error)) note = 'an error was expected but none was raised'
                write (stdout, '(a)') "  FAIL  "//suite%name//" "//tests(i)%name//": "//note//reported
            end if
            if (allocated(error)) deallocate (error)
        end do
    end subroutine run_testsuite

    subroutine check_logical(error, condition, message)
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in) :: condition
        character(len=*), intent(in) :: message
        if (.not. condition) call fatal_error(error, message)
    end subroutine check_logical

    !> |actual - expected| <= max(abs_tol, rel_tol*|expected|)
    subroutine check_real(error, actual, expected, message, rel, abs)
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in) :: actual, expected
        character(len=*), intent(in) :: message
        real(dp), intent(in), optional :: rel, abs
        real(dp) :: tol
        character(len=160) :: buf
        tol = 0.0_dp
        if (present(rel)) tol = max(tol, rel*dabs(expected))
        if (present(abs)) tol = max(tol, abs)
        if (.not. dabs(actual - expected) <= tol) then
            write (buf, '(a,es23.15,a,es23.15,a,es9.2,a,es9.2)') " actual ", actual, " expected ", expected, &
                " |diff| ", dabs(actual - expected), " > tol ", tol
            call fatal_error(error, message//trim(buf))
        end if
    end subroutine check_real

    subroutine check_int(error, actual, expected, message)
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in) :: actual, expected
        character(len=*), intent(in) :: message
        character(len=64) :: buf
        if (actual /= expected) then
            write (buf, '(a,i0,a,i0)') " actual ", actual, " expected ", expected
            call fatal_error(error, message//trim(buf))
        end if
    end subroutine check_int

    pure real(dp) function rel_error(actual, expected) result(r)
        real(dp), intent(in) :: actual, expected
        r = dabs(actual - expected)/dabs(expected)
    end function rel_error

end module testsuite
