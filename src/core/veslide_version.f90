!> Provenance: version, compiler, build options, git revision, time
module veslide_version
    use, intrinsic :: iso_fortran_env, only: compiler_version, compiler_options
    implicit none
    private
    public :: veslide_version_number, version_string, compiler_string, compiler_flags, git_revision, utc_timestamp

    !> The package version; a test checks that it equals the version in fpm.toml
    character(len=*), parameter :: veslide_version_number = "0.4.0"

contains

    function version_string() result(v)
        character(len=:), allocatable :: v
        v = veslide_version_number
    end function version_string

    function compiler_string() result(v)
        character(len=:), allocatable :: v
        v = compiler_version()
    end function compiler_string

    function compiler_flags() result(v)
        character(len=:), allocatable :: v
        v = compiler_options()
    end function compiler_flags

    !> Git revision of the source tree, from VESLIDE_GIT_REVISION (set by the project's scripts)
    function git_revision() result(v)
        character(len=:), allocatable :: v
        character(len=128) :: buf
        integer :: n, stat
        call get_environment_variable('VESLIDE_GIT_REVISION', buf, n, stat)
        if (stat == 0 .and. n > 0) then
            v = trim(buf)
        else
            v = 'unknown'
        end if
    end function git_revision

    !> ISO 8601 time with the zone offset of the machine (UTC on the project's machines)
    function utc_timestamp() result(v)
        character(len=:), allocatable :: v
        character(len=8) :: d
        character(len=10) :: t
        character(len=5) :: z
        call date_and_time(d, t, z)
        v = d(1:4)//'-'//d(5:6)//'-'//d(7:8)//'T'//t(1:2)//':'//t(3:4)//':'//t(5:6)//z(1:3)//':'//z(4:5)
    end function utc_timestamp

end module veslide_version
